#include "calibrate/numa_topology.hpp"

#include <pagecache/error.hpp>

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace pagecache::calibrate {

namespace {

// Far above any machine's CPU or node numbers, and far below int's limit.
constexpr int kLargest = 1 << 22;

int list_number(std::string_view digits, std::string_view item) {
  if (digits.empty() || digits.size() > 7 || digits.find_first_not_of("0123456789") != std::string_view::npos) {
    throw std::invalid_argument(fmt::format("'{}' is not a number or a range of numbers", item));
  }
  int value = 0;
  for (const char d : digits) value = value * 10 + (d - '0');
  if (value > kLargest) throw std::invalid_argument(fmt::format("{} is beyond any CPU or node number", value));
  return value;
}

std::string read_file_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(fmt::format("{}: cannot read it: {}", file.string(), std::error_code(errno, std::generic_category()).message()));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The file's list, or an error naming the file.
std::vector<int> read_list(const std::filesystem::path& file, std::string& text) {
  text = read_file_text(file);
  try {
    return parse_kernel_list(text);
  } catch (const std::invalid_argument& e) {
    throw Error(fmt::format("{}: not in the kernel's list format (such as \"0-15,32-47\"): {}", file.string(), e.what()));
  }
}

}  // namespace

std::vector<int> parse_kernel_list(std::string_view text) {
  if (!text.empty() && text.back() == '\n') text.remove_suffix(1);
  std::vector<int> numbers;
  if (text.empty()) return numbers;
  std::size_t at = 0;
  while (true) {
    const std::size_t comma = text.find(',', at);
    const std::string_view item = text.substr(at, comma == std::string_view::npos ? std::string_view::npos : comma - at);
    const std::size_t dash = item.find('-');
    const int first = list_number(item.substr(0, dash), item);
    const int last = dash == std::string_view::npos ? first : list_number(item.substr(dash + 1), item);
    if (last < first) throw std::invalid_argument(fmt::format("the range {} goes down", item));
    if (!numbers.empty() && first <= numbers.back()) throw std::invalid_argument(fmt::format("{} comes after {}: not in increasing order", item, numbers.back()));
    for (int n = first; n <= last; ++n) numbers.push_back(n);
    if (comma == std::string_view::npos) return numbers;
    at = comma + 1;
  }
}

std::string kernel_list_text(const std::vector<int>& numbers) {
  std::string text;
  for (std::size_t i = 0; i < numbers.size();) {
    std::size_t j = i;
    while (j + 1 < numbers.size() && numbers[j + 1] == numbers[j] + 1) ++j;
    text += fmt::format("{}{}", text.empty() ? "" : ",", numbers[i]);
    if (j > i) text += fmt::format("-{}", numbers[j]);
    i = j + 1;
  }
  return text;
}

NumaTopology read_numa_topology(const std::filesystem::path& root) {
  NumaTopology t;
  t.root = root;
  std::error_code ec;
  if (!std::filesystem::exists(root, ec)) {
    t.nodes.push_back(NumaNode{0, {}});
    return t;
  }
  const std::filesystem::path online = root / "online";
  const std::vector<int> ids = read_list(online, t.online);
  if (!t.online.empty() && t.online.back() == '\n') t.online.pop_back();
  if (ids.empty()) throw Error(fmt::format("{}: no node online", online.string()));
  for (const int id : ids) {
    std::string text;
    t.nodes.push_back(NumaNode{id, read_list(root / fmt::format("node{}", id) / "cpulist", text)});
  }
  return t;
}

}  // namespace pagecache::calibrate
