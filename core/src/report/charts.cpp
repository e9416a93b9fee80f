#include "plumage/charts.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iomanip>

#include "plumage/atomic_file.hpp"
#include "plumage/data_paths.hpp"
#include "plumage/error.hpp"

extern char** environ;

namespace plumage {

namespace fs = std::filesystem;

namespace {

// Runs argv without a shell (no quoting problems); returns the exit status.
int run_process(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return 127;
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return 127;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

// Debian's python3-matplotlib belongs to /usr/bin/python3, which may not be the `python3`
// first on PATH (pyenv, venvs); $PLUMAGE_PYTHON overrides both.
std::string python_interpreter() {
  if (const char* env = std::getenv("PLUMAGE_PYTHON")) return env;
  std::error_code ec;
  if (fs::exists("/usr/bin/python3", ec)) return "/usr/bin/python3";
  return "python3";
}

}  // namespace

void draw_script_chart(const std::string& script_name, const std::vector<std::string>& inputs,
                       const fs::path& png, const std::string& title,
                       const std::vector<std::string>& extra_args) {
  const fs::path script = data_directory() / script_name;
  check_output_path(png);
  create_output_directory(png.parent_path());
  const fs::path temp_png = fs::path(png).concat(".tmp.png");
  const std::string python = python_interpreter();
  std::vector<std::string> args{python, script.string()};
  args.insert(args.end(), inputs.begin(), inputs.end());
  args.push_back(temp_png.string());
  args.push_back("--title");
  args.push_back(title);
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  const int status = run_process(args);
  std::error_code ec;
  if (status != 0 || !fs::exists(temp_png)) {
    fs::remove(temp_png, ec);
    throw Error("drawing " + png.string() + " failed (" + python + " " + script.string() +
                " exited with status " + std::to_string(status) +
                "; is python3-matplotlib installed?)");
  }
  check_output_path(png);  // again: the drawing took a while
  fs::rename(temp_png, png);
}

void draw_line_chart(const LineChart& chart, const fs::path& png) {
  const fs::path csv = fs::path(png).concat(".data.csv.tmp");
  {
    std::ofstream out(csv);
    out << "panel,series,x,y,style\n" << std::setprecision(10);
    for (const auto& p : chart.points) {
      out << '"' << p.panel << "\",\"" << p.series << "\"," << p.x << ',' << p.y << ',' << (p.dashed ? "dashed" : "solid") << '\n';
    }
    if (!out) throw Error(csv.string() + ": cannot write chart data");
  }
  try {
    draw_script_chart("plot_lines.py", {csv.string()}, png, chart.title,
                      {"--xlabel", chart.x_label, "--ylabel", chart.y_label});
  } catch (...) {
    std::error_code ec;
    fs::remove(csv, ec);
    throw;
  }
  std::error_code ec;
  fs::remove(csv, ec);
}

}  // namespace plumage
