// Every option of every `ldv` command, given hostile values (NaN, infinities, extremes, negative counts,
// empty and huge text, /dev/zero as a file): each run ends by itself within its time and memory limits,
// without a signal. The default suite runs a fixed-seed sample; the `fuzz` label runs every combination.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>

#include "cli_run.hpp"
#include "sim/simulator.hpp"

namespace ldv {
namespace {
namespace fs = std::filesystem;
using test::run_ldv;

struct OptionSpec {
  std::string name, type;  // type: FLOAT, INT, TEXT, FLAG
  int arity = 1;
};

// The options `ldv CMD --help` lists, with their value type.
std::vector<OptionSpec> options_of(const std::vector<std::string>& command) {
  std::vector<std::string> args = command;
  args.push_back("--help");
  const auto r = run_ldv(args, 20.0);
  std::vector<OptionSpec> out;
  std::istringstream in(r.output);
  const std::regex opt(R"(^\s+(?:-\w,)?(--[\w-]+)(?:\s+(FLOAT|INT|TEXT|UINT)(?:\s+x\s+(\d+))?)?)");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, opt) || m[1] == "--help") continue;
    OptionSpec s{m[1], m[2].matched ? m[2].str() : "FLAG", m[3].matched ? std::stoi(m[3]) : 1};
    out.push_back(s);
  }
  return out;
}

const fs::path& work_dir();

std::string zero_link() {
  const fs::path link = work_dir() / "zero_link";
  std::error_code ec;
  if (!fs::is_symlink(link, ec)) fs::create_symlink("/dev/zero", link, ec);
  return link.string();
}

std::vector<std::string> hostile_values(const std::string& type) {
  if (type == "FLOAT") return {"nan", "inf", "-inf", "1e308", "-1e308", "0", "-1", "1e-300", "1e999"};
  if (type == "INT" || type == "UINT") return {"-1", "0", "2147483648", "-2147483649", "999999999"};
  // /dev/zero through a link of our own: an input that never ends, and, if a writer ever renamed over
  // its output path again (it once replaced /dev/zero itself), only the link would go.
  if (type == "TEXT") return {"", zero_link(), "/nonexistent/x", std::string(20000, 'a'), "nan", "-"};
  return {""};
}

struct Command {
  std::vector<std::string> base;  // a valid run
};

const fs::path& work_dir() {
  static const fs::path d = [] {
    const fs::path dir = fs::temp_directory_path() / ("ldv_option_fuzz_" + std::to_string(getpid()));
    fs::create_directories(dir);
    sim::SimRequest req;
    req.grade = "3dm-gx2-typical";
    req.seed = 13;
    req.duration_s = 40.0;
    req.scenario = "drive";
    req.gnss_rate_hz = 5.0;
    sim::SimResult s = sim::simulate(req);
    sim::write_outputs(s, (dir / "drive").string());
    std::ofstream csv(dir / "rate.csv");
    csv << "t,x\n";
    std::mt19937_64 rng(1);
    std::normal_distribution<double> n;
    for (int i = 0; i < 3000; ++i) csv << 0.01 * i << "," << 1e-3 * n(rng) << "\n";
    return dir;
  }();
  return d;
}

std::map<std::string, Command> commands() {
  const fs::path d = work_dir();
  const std::string cfg = (d / "drive" / "kfgins.yaml").string(), nav = (d / "drive" / "truth.nav").string();
  return {
      {"nav", {{"nav", "--kfgins-config", cfg, "--out", (d / "o.nav").string(), "--quiet"}}},
      {"smooth", {{"smooth", "--kfgins-config", cfg, "--out", (d / "s.nav").string(), "--quiet"}}},
      {"outage",
       {{"outage", "--kfgins-config", cfg, "--lengths", "5", "--converge", "10", "--recovery", "5", "--quiet"}}},
      {"diagnose", {{"diagnose", "--kfgins-config", cfg, "--max-add", "0"}}},
      {"allan", {{"allan", (d / "rate.csv").string(), "--time-column", "t", "--curve-only"}}},
      {"compare", {{"compare", nav, nav}}},
      {"report", {{"report", "--nav", nav, "--out", (d / "page").string()}}},
      {"sim", {{"sim", "--duration", "5", "--out", (d / "sim_out").string()}}},
  };
}

struct Trial {
  std::vector<std::string> args;
  std::string label;
};

std::vector<Trial> all_trials() {
  std::vector<Trial> trials;
  for (const auto& [name, c] : commands()) {
    const std::vector<std::string> cmd{c.base.front()};
    for (const OptionSpec& o : options_of(cmd)) {
      for (const std::string& v : hostile_values(o.type)) {
        std::vector<std::string> args = c.base;
        // The option replaces its value in the base run when it is there.
        const auto it = std::find(args.begin(), args.end(), o.name);
        if (it != args.end()) args.erase(it, std::min(args.end(), it + 1 + (o.type == "FLAG" ? 0 : o.arity)));
        args.push_back(o.name);
        if (o.type != "FLAG")
          for (int k = 0; k < o.arity; ++k) args.push_back(v);
        trials.push_back(
            {args, name + " " + o.name + " " +
                       (v.size() > 40 ? v.substr(0, 10) + "...(" + std::to_string(v.size()) + " chars)" : v)});
      }
    }
  }
  return trials;
}

void run_trials(const std::vector<Trial>& trials) {
  int failures = 0;
  for (const Trial& t : trials) {
    const auto r = run_ldv(t.args, 60.0, 4L << 30);
    const bool ok = !r.timed_out && r.signal == 0;
    if (!ok) {
      ++failures;
      ADD_FAILURE() << t.label << ": " << (r.timed_out ? "hung (60 s)" : "signal " + std::to_string(r.signal)) << "\n"
                    << r.output.substr(0, 2000);
    }
  }
  std::printf("[ info ] %zu option trials, %d crashed or hung\n", trials.size(), failures);
}

}  // namespace

#ifndef LDV_FUZZ_FULL
TEST(OptionFuzz, FixedSeedSampleOfEveryCommandsOptions) {
  std::vector<Trial> trials = all_trials();
  ASSERT_GT(trials.size(), 200u) << "the commands' options were not found";
  std::mt19937_64 rng(20261123);
  std::shuffle(trials.begin(), trials.end(), rng);
  trials.resize(80);
  run_trials(trials);
}
#else
TEST(OptionFuzzFull, EveryOptionOfEveryCommand) { run_trials(all_trials()); }
#endif

}  // namespace ldv
