#include "plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

extern char** environ;

namespace mechsim::plot {
namespace fs = std::filesystem;
namespace {

// Text for a script or data-file line: a line break would end the command or comment.
std::string one_line(std::string_view text) {
  std::string out(text);
  for (char& c : out) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return out;
}

// A single-quoted gnuplot string: only '' needs escaping there, and the `noenhanced`
// terminal option keeps '_' and '^' in labels literal.
std::string gp_string(std::string_view text) {
  std::string out = "'";
  for (char c : one_line(text)) {
    if (c == '\'') out += '\'';
    out += c;
  }
  return out + "'";
}

std::string number(double v) {
  if (std::isnan(v)) return "NaN";  // gnuplot leaves a gap
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

bool style_clause(const std::string& style, std::string* clause) {
  if (style == "lines") {
    *clause = "with lines lw 1.5";
  } else if (style == "points") {
    *clause = "with points pt 7 ps 0.5";
  } else if (style == "linespoints") {
    *clause = "with linespoints lw 1.5 pt 7 ps 0.5";
  } else if (style == "dashed") {
    *clause = "with lines lw 1.5 dt 2";
  } else {
    return false;
  }
  return true;
}

bool fail(std::string* why, std::string message) {
  if (why) *why = std::move(message);
  return false;
}

// A private directory under the system temp dir, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "mechsim-plot-XXXXXX").string();
    if (mkdtemp(pattern.data())) path_ = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    if (!path_.empty()) fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Runs `gnuplot script` with stdout and stderr going to `log`. Returns the exit status,
// or -1 with *spawn_error set when gnuplot could not be started.
int run_gnuplot(const fs::path& script, const fs::path& log, std::string* spawn_error) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::string program = "gnuplot";
  std::string script_arg = script.string();
  char* argv[] = {program.data(), script_arg.data(), nullptr};
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    *spawn_error = rc == ENOENT ? "gnuplot is not installed (not found on PATH)"
                                : std::string("cannot start gnuplot: ") + std::strerror(rc);
    return -1;
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) {
      *spawn_error = std::string("waiting for gnuplot: ") + std::strerror(errno);
      return -1;
    }
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

std::string read_tail(const fs::path& path, std::size_t max_chars) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s.size() > max_chars ? "..." + s.substr(s.size() - max_chars) : s;
}

// Writes the data files and returns the script body (everything after the terminal line).
bool write_script_body(const Figure& figure, const fs::path& dir, std::string* body,
                       std::string* why) {
  std::ostringstream gp;
  gp << "set grid\n";
  // The legend below the plot area, never over a curve.
  gp << "set key below\n";
  gp << "set multiplot layout " << figure.panels.size() << ",1";
  if (!figure.title.empty()) gp << " title " << gp_string(figure.title);
  gp << "\n";
  for (std::size_t p = 0; p < figure.panels.size(); ++p) {
    const Panel& panel = figure.panels[p];
    gp << "\n# --- panel " << p + 1 << ": " << one_line(panel.title) << "\n";
    gp << "set title " << gp_string(panel.title) << "\n";
    gp << "set xlabel " << gp_string(panel.xlabel) << "\n";
    gp << "set ylabel " << gp_string(panel.ylabel) << "\n";
    gp << "unset logscale\n";
    if (panel.logx) gp << "set logscale x\n";
    if (panel.logy) gp << "set logscale y\n";
    if (panel.yrange) {
      gp << "set yrange [" << number(panel.yrange->first) << ":" << number(panel.yrange->second)
         << "]\n";
    } else {
      gp << "set autoscale y\n";
    }
    gp << (panel.equal_axes ? "set size ratio -1\n" : "set size noratio\n");

    std::vector<std::string> plots;
    for (std::size_t s = 0; s < panel.series.size(); ++s) {
      const Series& series = panel.series[s];
      if (series.x.size() != series.y.size()) {
        return fail(why, "series '" + series.label + "' has " + std::to_string(series.x.size()) +
                             " x values but " + std::to_string(series.y.size()) + " y values");
      }
      std::string clause;
      if (!style_clause(series.style, &clause)) {
        return fail(why, "series '" + series.label + "': unknown style '" + series.style +
                             "' (lines, points, linespoints, dashed)");
      }
      if (series.x.empty()) continue;  // gnuplot refuses an empty data file
      const std::string data_name =
          "panel" + std::to_string(p + 1) + "_series" + std::to_string(s + 1) + ".dat";
      std::ofstream data(dir / data_name);
      data << "# " << one_line(series.label) << "\n# x y\n";
      for (std::size_t i = 0; i < series.x.size(); ++i) {
        data << number(series.x[i]) << ' ' << number(series.y[i]) << '\n';
      }
      if (!data) return fail(why, "cannot write " + (dir / data_name).string());
      plots.push_back(gp_string((dir / data_name).string()) + " using 1:2 " + clause + " title " +
                      gp_string(series.label));
    }
    for (const auto& [y, label] : panel.hlines) {
      plots.push_back(number(y) + " with lines lw 1 dt 3 lc rgb '#606060' title " +
                      gp_string(label));
    }
    if (plots.empty()) {
      gp << "set label 1 'no data' at graph 0.5,0.5 center\n";
      gp << "plot [0:1] [0:1] NaN notitle\n";
      gp << "unset label 1\n";
      continue;
    }
    gp << "plot ";
    for (std::size_t i = 0; i < plots.size(); ++i) gp << (i ? ", \\\n     " : "") << plots[i];
    gp << "\n";
  }
  gp << "\nunset multiplot\n";
  *body = gp.str();
  return true;
}

}  // namespace

bool gnuplot_available() {
  const char* path = std::getenv("PATH");
  std::string_view dirs = path ? path : "/usr/bin:/bin";
  while (!dirs.empty()) {
    const std::size_t colon = dirs.find(':');
    const std::string dir(dirs.substr(0, colon));
    if (!dir.empty() && access((fs::path(dir) / "gnuplot").c_str(), X_OK) == 0) return true;
    if (colon == std::string_view::npos) break;
    dirs.remove_prefix(colon + 1);
  }
  return false;
}

bool write_png(const Figure& figure, const std::string& png_path, std::string* why) {
  if (figure.panels.empty()) return fail(why, "the figure has no panels");
  if (figure.width_px <= 0 || figure.height_px_per_panel <= 0) {
    return fail(why, "the figure size must be positive");
  }
  TempDir dir;
  if (dir.path().empty()) return fail(why, "cannot create a temporary directory for the plot");

  std::string body;
  if (!write_script_body(figure, dir.path(), &body, why)) return false;
  const int height = figure.height_px_per_panel * static_cast<int>(figure.panels.size()) +
                     (figure.title.empty() ? 0 : 30);
  const fs::path image = dir.path() / "figure.png";
  const fs::path script = dir.path() / "figure.gp";
  const fs::path log = dir.path() / "gnuplot.log";

  // pngcairo draws anti-aliased lines; the libgd `png` terminal is the fallback.
  std::string output;
  for (const char* terminal : {"pngcairo", "png"}) {
    std::ofstream gp(script);
    gp << "# mechsim figure: " << one_line(figure.title) << "\n"
       << "set terminal " << terminal << " noenhanced size " << figure.width_px << "," << height
       << "\n"
       << "set output " << gp_string(image.string()) << "\n"
       << body;
    gp.close();
    if (!gp) return fail(why, "cannot write the gnuplot script " + script.string());

    std::string spawn_error;
    const int status = run_gnuplot(script, log, &spawn_error);
    if (status < 0) return fail(why, spawn_error);
    output = read_tail(log, 600);
    if (status == 0) break;
    if (output.find("unknown or ambiguous terminal type") == std::string::npos) {
      return fail(why, "gnuplot failed (exit status " + std::to_string(status) + "): " + output);
    }
  }
  std::error_code ec;
  if (!fs::exists(image, ec) || fs::file_size(image, ec) == 0) {
    return fail(why, "gnuplot wrote no image: " + output);
  }
  // rename() is atomic but does not cross file systems; copy then.
  fs::rename(image, png_path, ec);
  if (ec) {
    ec.clear();
    fs::copy_file(image, png_path, fs::copy_options::overwrite_existing, ec);
    if (ec) return fail(why, "cannot write " + png_path + ": " + ec.message());
  }
  return true;
}

}  // namespace mechsim::plot
