#include "validate/fio_kept.hpp"

#include "formats/common/json_text.hpp"
#include "formats/common/text_file.hpp"
#include "validate/csv.hpp"

#include <pagecache/error.hpp>
#include <pagecache/units.hpp>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <climits>
#include <map>

namespace pagecache::validate {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::int64_t whole(const json& object, const char* key, const std::string& where) {
  const auto it = object.find(key);
  if (it == object.end() || !it->is_number_integer() || it->get<std::int64_t>() < 0) {
    throw ConfigError(fmt::format("{}: \"{}\" is missing or not a whole number of at least 0", where, key));
  }
  return it->get<std::int64_t>();
}

FioMeasuredDirection direction(const json& job, const char* name, const std::string& where) {
  const auto it = job.find(name);
  if (it == job.end() || !it->is_object()) throw ConfigError(fmt::format("{}: no \"{}\" object", where, name));
  const std::string at = fmt::format("{}: {}", where, name);
  return {whole(*it, "io_bytes", at), whole(*it, "bw_bytes", at), whole(*it, "runtime", at)};
}

// A name the manifest gives: a file of the folder itself, nothing beside or below it.
std::string plain_name(const CsvTable::Row& row, const char* column) {
  const std::string& name = row.text(column);
  if (name == "." || name == ".." || name.find('/') != std::string::npos) row.fail(column, fmt::format("'{}' is not a file name of this folder", shown(name)));
  return name;
}

}  // namespace

std::vector<FioMeasuredJob> parse_fio_report(std::string_view text, const std::string& file) {
  const json report = json::parse(text, nullptr, false);
  if (report.is_discarded() || !report.is_object()) throw ConfigError(fmt::format("{}: not a JSON object (fio --output-format=json's report)", file));
  formats::check_unique_keys(text, file);
  const auto jobs = report.find("jobs");
  if (jobs == report.end() || !jobs->is_array() || jobs->empty()) throw ConfigError(fmt::format("{}: no \"jobs\" array with a job", file));
  std::vector<FioMeasuredJob> out;
  for (std::size_t i = 0; i < jobs->size(); ++i) {
    const json& job = (*jobs)[i];
    const std::string where = fmt::format("{}: jobs[{}]", file, i);
    if (!job.is_object()) throw ConfigError(fmt::format("{}: not an object", where));
    const auto name = job.find("jobname");
    if (name == job.end() || !name->is_string()) throw ConfigError(fmt::format("{}: no \"jobname\" string", where));
    out.push_back({name->get<std::string>(), direction(job, "read", where), direction(job, "write", where)});
  }
  return out;
}

std::string fio_manifest(const std::vector<FioJobFileRuns>& runs) {
  std::string text = "job_file,repetition,json_file,memory_max,peak_memory\n";
  for (const FioJobFileRuns& f : runs)
    for (const FioRepetition& r : f.repetitions)
      text += fmt::format("{},{},{},{},{}\n", f.job_file, r.repetition, r.json_file, f.memory_max, r.peak_memory);
  return text;
}

bool is_fio_folder(const fs::path& folder) {
  std::error_code ec;
  return fs::exists(folder / kFioManifest, ec);
}

std::vector<FioJobFileRuns> load_fio_runs(const fs::path& folder) {
  const std::string manifest = (folder / kFioManifest).string();
  const CsvTable table(formats::read_text_file(manifest, "fio manifest"), manifest, {"job_file", "repetition", "json_file"},
                       {"memory_max", "peak_memory"});
  if (table.size() == 0) throw ConfigError(fmt::format("{}:1: no runs after the header", manifest));
  std::vector<FioJobFileRuns> runs;
  std::map<std::string, std::size_t> index;  // job file -> its entry in runs
  for (std::size_t i = 0; i < table.size(); ++i) {
    const CsvTable::Row row = table.row(i);
    const std::string job_file = plain_name(row, "job_file");
    const auto [at, fresh] = index.emplace(job_file, runs.size());
    if (fresh) {
      formats::read_text_file((folder / job_file).string(), "fio job file");  // its copy is there to simulate
      runs.push_back({job_file, {}, table.has("memory_max") ? row.whole("memory_max", 0, units::kMaxBytes) : 0});
    }
    FioJobFileRuns& f = runs[at->second];
    if (table.has("memory_max") && row.whole("memory_max", 0, units::kMaxBytes) != f.memory_max) {
      row.fail("memory_max", fmt::format("not the {} bytes of {}'s first repetition: its repetitions ran under one limit", f.memory_max, job_file));
    }
    const int repetition = static_cast<int>(row.whole("repetition", 1, INT_MAX));
    if (repetition != static_cast<int>(f.repetitions.size()) + 1) {
      row.fail("repetition", fmt::format("{} is not {}'s next repetition ({})", repetition, job_file, f.repetitions.size() + 1));
    }
    const std::string json_file = plain_name(row, "json_file");
    const std::string path = (folder / json_file).string();
    const std::int64_t peak = table.has("peak_memory") ? row.whole("peak_memory", -1, INT64_MAX) : -1;
    f.repetitions.push_back({repetition, json_file, parse_fio_report(formats::read_text_file(path, "fio report"), path), peak});
  }
  return runs;
}

}  // namespace pagecache::validate
