// `pcsim show` (to_toml) writes any name as a TOML string that reads back to the same name,
// and its opening comment survives any source path. Read back with the scenario loader and,
// for names the loader would refuse, with toml++'s parser alone.
#include <pagecache/scenario.hpp>
#include <pagecache/scenario_file.hpp>

#include <catch2/catch.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <random>
#include <string>
#include <vector>

using pagecache::parse_scenario;
using pagecache::Scenario;
using pagecache::to_toml;

namespace {

// Two hosts joined by a link, three files, an application and a workflow: every kind of name
// that to_toml writes, and every list.
const char* kScenario = R"(
[[hosts]]
name = "h1"
memory = "8 GB"
memory_read_bw = "1 GB/s"
memory_write_bw = "1 GB/s"
[[hosts.disks]]
name = "d1"
read_bw = "100 MB/s"
write_bw = "100 MB/s"
[[hosts]]
name = "h2"
memory = "8 GB"
memory_read_bw = "1 GB/s"
memory_write_bw = "1 GB/s"
[[hosts.disks]]
name = "d2"
read_bw = "100 MB/s"
write_bw = "100 MB/s"
[[links]]
name = "l"
bandwidth = "1 GB/s"
hosts = ["h1", "h2"]
[[files]]
name = "f1"
size = "1 GB"
[[files]]
name = "f2"
size = "1 GB"
host = "h2"
[[files]]
name = "f3"
size = "1 GB"
[[apps]]
name = "a"
[[apps.tasks]]
name = "t1"
read = ["f1", "f2"]
write = "f3"
delete = "f3"
[workflow]
name = "w"
[[workflow.tasks]]
name = "w1"
read = "f1"
[[workflow.tasks]]
name = "w2"
after = "w1"
)";

// Hostile, all valid UTF-8 and distinct: control characters, quotes, backslashes, TOML's
// own delimiters, line breaks at either end, non-ASCII and characters toml++ escapes.
const std::vector<std::string> kHostile = {
    "\x01start of heading",
    "del\x7F",
    "new\nline",
    "cr\rlf\r\n",
    "tab\there",
    "\"double\" quotes",
    "back\\slash\\",
    "'''three singles'''",
    "\"\"\"three doubles\"\"\"",
    "n\xC3\xA4me \xE5\x90\x8D \xF0\x9F\x9A\x80",
    "'single'\n'''\nmixed",
    "\nleading newline",
    "trailing quote'",
    "esc\x1B[0m",
    "nel\xC2\x85 ls\xE2\x80\xA8 bom\xEF\xBB\xBF",
    "# not a comment",
    "= [ ] { } , .",
    "\\u0041 not an escape",
    "",
};

// Every name in `s` (definitions and references) mapped through `rename`.
void rename_all(Scenario& s, const std::map<std::string, std::string>& rename) {
  auto re = [&](std::string& name) { name = rename.at(name); };
  auto re_task = [&](pagecache::TaskSpec& t) {
    re(t.name);
    for (auto* list : {&t.reads, &t.writes, &t.deletes, &t.after}) {
      for (auto& n : *list) re(n);
    }
  };
  for (auto& h : s.hosts) {
    re(h.name);
    for (auto& d : h.disks) re(d.name);
  }
  for (auto& l : s.links) re(l.name), re(l.host_a), re(l.host_b);
  for (auto& f : s.files) re(f.name), re(f.host), re(f.disk);
  for (auto& a : s.apps) {
    re(a.name), re(a.host);
    for (auto& t : a.tasks) re_task(t);
  }
  for (auto& w : s.workflows) {
    re(w.name);
    for (auto& h : w.hosts) re(h);
    for (auto& t : w.tasks) re_task(t);
  }
}

// All the names of `s`, in order.
std::vector<std::string> names(const Scenario& s) {
  std::vector<std::string> out{s.title};
  auto task = [&](const pagecache::TaskSpec& t) {
    out.push_back(t.name);
    for (const auto* list : {&t.reads, &t.writes, &t.deletes, &t.after}) out.insert(out.end(), list->begin(), list->end());
  };
  for (const auto& h : s.hosts) {
    out.push_back(h.name);
    for (const auto& d : h.disks) out.push_back(d.name);
  }
  for (const auto& l : s.links) out.insert(out.end(), {l.name, l.host_a, l.host_b});
  for (const auto& f : s.files) out.insert(out.end(), {f.name, f.host, f.disk});
  for (const auto& a : s.apps) {
    out.insert(out.end(), {a.name, a.host});
    for (const auto& t : a.tasks) task(t);
  }
  for (const auto& w : s.workflows) {
    out.push_back(w.name);
    out.insert(out.end(), w.hosts.begin(), w.hosts.end());
    for (const auto& t : w.tasks) task(t);
  }
  return out;
}

// The same names as names(), read from the shown TOML by toml++ alone (the loader refuses
// some names an embedding program can make, such as those with control characters).
std::vector<std::string> names_in(const toml::table& t) {
  std::vector<std::string> out{t["title"].value_or(std::string())};
  auto str = [](toml::node_view<const toml::node> n) { return n.value<std::string>().value(); };
  auto list = [&](toml::node_view<const toml::node> n) {
    for (const auto& item : *n.as_array()) out.push_back(item.value<std::string>().value());
  };
  auto tasks = [&](toml::node_view<const toml::node> n, bool with_after) {
    for (const auto& task : *n.as_array()) {
      const toml::table& k = *task.as_table();
      out.push_back(str(k["name"]));
      list(k["read"]), list(k["write"]), list(k["delete"]);
      if (with_after) list(k["after"]);
    }
  };
  for (const auto& h : *t["hosts"].as_array()) {
    out.push_back(str((*h.as_table())["name"]));
    for (const auto& d : *(*h.as_table())["disks"].as_array()) out.push_back(str((*d.as_table())["name"]));
  }
  for (const auto& l : *t["links"].as_array()) out.push_back(str((*l.as_table())["name"])), list((*l.as_table())["hosts"]);
  for (const auto& f : *t["files"].as_array()) {
    for (const char* key : {"name", "host", "disk"}) out.push_back(str((*f.as_table())[key]));
  }
  for (const auto& a : *t["apps"].as_array()) {
    out.push_back(str((*a.as_table())["name"])), out.push_back(str((*a.as_table())["host"]));
    tasks((*a.as_table())["tasks"], false);
  }
  out.push_back(str(t["workflow"]["name"])), out.push_back(str(t["workflow"]["host"]));
  tasks(t["workflow"]["tasks"], true);
  return out;
}

}  // namespace

TEST_CASE("a scenario whose names hold control characters, quotes and non-ASCII shows as TOML that reads back the same",
          "[scenario][show]") {
  const Scenario s = parse_scenario(kScenario, "show_test");
  const std::vector<std::string> plain = {"h1", "d1", "h2", "d2", "l", "f1", "f2", "f3", "a", "t1", "w", "w1", "w2"};
  // Each name of `pool` in turn in every place, shifted by one per round so that all meet;
  // read back by toml++, and by the loader too for the names it accepts.
  auto show_and_read = [&](const std::vector<std::string>& pool, bool through_loader) {
    for (std::size_t round = 0; round < pool.size(); ++round) {
      std::map<std::string, std::string> rename;
      for (std::size_t i = 0; i < plain.size(); ++i) rename[plain[i]] = pool[(round + i) % pool.size()] + std::to_string(i);
      Scenario hostile = s;
      rename_all(hostile, rename);
      hostile.title = pool[round];
      const std::string text = to_toml(hostile);
      INFO("round " << round << ":\n" << text);
      toml::table table;
      REQUIRE_NOTHROW(table = toml::parse(text));
      CHECK(names_in(table) == names(hostile));
      if (!through_loader) continue;
      Scenario back;
      REQUIRE_NOTHROW(back = parse_scenario(text, "shown"));
      CHECK(names(back) == names(hostile));
      // Shown again, the same document (apart from the comment naming the source).
      const std::string again = to_toml(back);
      CHECK(again.substr(again.find('\n')) == text.substr(text.find('\n')));
    }
  };
  show_and_read(kHostile, false);
  // Through the loader, the names it accepts: it refuses control characters and a leading
  // = + - @ from issue 15 on (an embedding program can still make them: the pass above).
  std::vector<std::string> loadable;
  std::copy_if(kHostile.begin(), kHostile.end(), std::back_inserter(loadable), [](const std::string& n) {
    return !n.empty() && std::string("=+-@").find(n.front()) == std::string::npos &&
           std::none_of(n.begin(), n.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7F; });
  });
  REQUIRE(loadable.size() >= 8);
  show_and_read(loadable, true);
}

TEST_CASE("any valid UTF-8 string in a name shows as a TOML string that toml++ reads back the same", "[scenario][show]") {
  Scenario s = parse_scenario(kScenario, "show_test");
  // Code points drawn from the awkward ones: every C0 control, DEL, C1, quotes, backslash,
  // TOML punctuation, separators, a BOM, U+FFFD and non-BMP.
  std::vector<char32_t> alphabet = {'"', '\'', '\\', '#', '=', '[', ']', '{', '}', ',', '.', ' ', 'a', 'Z', '0', 0x7F, 0x80, 0x85,
                                    0x9F, 0xA0, 0xE9, 0x2028, 0x2029, 0x202E, 0xFEFF, 0xFFFD, 0xFFFF, 0x1F680, 0x10FFFF};
  for (char32_t c = 0; c < 0x20; ++c) alphabet.push_back(c);
  auto utf8 = [](char32_t c) {
    std::string out;
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6)), out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12)), out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18)), out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F)), out += static_cast<char>(0x80 | (c & 0x3F));
    }
    return out;
  };
  std::mt19937 random(15);
  for (int n = 0; n < 2000; ++n) {
    std::string name;
    const int length = std::uniform_int_distribution<int>(0, 12)(random);
    for (int i = 0; i < length; ++i) name += utf8(alphabet[std::uniform_int_distribution<std::size_t>(0, alphabet.size() - 1)(random)]);
    Scenario named = s;
    named.apps[0].name = name;
    named.apps[0].tasks[0].reads = {name, "x"};
    const std::string text = to_toml(named);
    INFO(text);
    toml::table table;
    REQUIRE_NOTHROW(table = toml::parse(text));
    CHECK(table["apps"][0]["name"].value<std::string>() == name);
    CHECK(table["apps"][0]["tasks"][0]["read"][0].value<std::string>() == name);
    CHECK(table["apps"][0]["tasks"][0]["read"][1].value<std::string>() == "x");
  }
}

TEST_CASE("pcsim show's opening comment stays one comment line whatever the source path holds", "[scenario][show]") {
  Scenario s = parse_scenario(kScenario, "show_test");
  s.source = "dir\n[hosts]\r\x01\x7F\xC2\x9B\x1B[2J \xFF\xE2\x82/x.toml";
  const std::string text = to_toml(s);
  const std::string first = text.substr(0, text.find('\n'));
  INFO(text);
  CHECK(first == "# resolved from dir\\n[hosts]\\r\\u0001\\u007f\\u009b\\u001b[2J \xEF\xBF\xBD\xEF\xBF\xBD/x.toml");
  Scenario back;
  REQUIRE_NOTHROW(back = parse_scenario(text, "shown"));
  CHECK(names(back) == names(s));
}

TEST_CASE("a name that is not valid UTF-8 shows with U+FFFD in place of each ill-formed part", "[scenario][show]") {
  // Only an embedding program can make one (the loader reads TOML, which is UTF-8); TOML
  // strings are Unicode, so the name is shown as close as TOML allows.
  Scenario s = parse_scenario(kScenario, "show_test");
  s.title = "bad \xFF title \xC0\xAF";
  const toml::table table = toml::parse(to_toml(s));
  CHECK(table["title"].value<std::string>() == "bad \xEF\xBF\xBD title \xEF\xBF\xBD\xEF\xBF\xBD");
}

TEST_CASE("a host's speed shows as flop/s that read back to the same double, and a host without one shows none", "[scenario][show]") {
  for (const std::string speed : {"\"1.234567891234Gf\"", "\"2.4Gf\"", "3e9", "1"}) {
    std::string text = kScenario;
    text.replace(text.find("name = \"h1\"\n"), 12, "name = \"h1\"\nspeed = " + speed + "\n");
    const Scenario first = parse_scenario(text, "speed.toml");
    REQUIRE(first.hosts[0].speed > 0.0);
    const std::string shown = to_toml(first);
    const Scenario again = parse_scenario(shown, "speed.toml");  // the same source: the same opening comment
    INFO(speed << "\n" << shown);
    CHECK(again.hosts[0].speed == first.hosts[0].speed);
    CHECK(again.hosts[1].speed == 0.0);
    CHECK(to_toml(again) == shown);
  }
  CHECK(to_toml(parse_scenario(kScenario, "plain.toml")).find("speed =") == std::string::npos);
}

TEST_CASE("a host's request_time is read, refused out of range naming its key, and shown only when set", "[scenario][show]") {
  std::string text = kScenario;
  text.replace(text.find("name = \"h1\"\n"), 12, "name = \"h1\"\nrequest_time = \"20 us\"\n");
  const Scenario s = parse_scenario(text, "request.toml");
  CHECK(s.hosts[0].request_time == Catch::Detail::Approx(20e-6));
  CHECK(s.hosts[1].request_time == 0.0);
  CHECK(parse_scenario(to_toml(s), "request.toml").hosts[0].request_time == s.hosts[0].request_time);
  CHECK(to_toml(parse_scenario(kScenario, "plain.toml")).find("request_time") == std::string::npos);
  std::string negative = kScenario;
  negative.replace(negative.find("name = \"h1\"\n"), 12, "name = \"h1\"\nrequest_time = \"2 s\"\n");
  CHECK_THROWS_WITH(parse_scenario(negative, "bad.toml"), Catch::Contains("bad.toml:4") && Catch::Contains("request_time"));
}
