#include "figure_files.h"

#include <filesystem>
#include <stdexcept>

namespace mechsim::plot {

PlotOutcome write_figures(const std::string& dir, const std::vector<NamedFigure>& figures) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create the plot directory " + dir + ": " + ec.message());
  PlotOutcome out;
  for (const auto& f : figures) {
    const std::string path = (std::filesystem::path(dir) / f.file_name).string();
    std::string why;
    if (write_png(f.figure, path, &why))
      out.files.push_back(path);
    else
      out.problems.push_back(path + ": " + why);
  }
  return out;
}

}  // namespace mechsim::plot
