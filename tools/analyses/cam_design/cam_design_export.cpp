#include "cam_design_export.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "atomic_file.h"
#include "csv.h"
#include "mechsim/models/constants.h"

namespace mechsim::tools::cam_design {

namespace {

using models::degree;

// One group: the code right-aligned in three columns (as AutoCAD writes it), then the value.
void group(std::string& out, int code, const std::string& value) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "%3d\n", code);
  out += buf;
  out += value;
  out += '\n';
}

// Coordinates in mm with 1e-6 mm resolution: far below any machining tolerance.
std::string coordinate(double metres) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6f", metres * 1e3);
  return buf;
}

}  // namespace

std::vector<ContourPoint> contour_points(const CamDesignResult& result) {
  std::vector<ContourPoint> out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (result.roller) {
    for (const auto& s : result.roller->contour)
      out.push_back({s.theta_rad, s.pitch.x, s.pitch.y, s.contour.x, s.contour.y});
  } else if (result.flat_face) {
    for (const auto& p : result.flat_face->points) out.push_back({p.theta_rad, nan, nan, p.contour.x, p.contour.y});
  }
  return out;
}

void write_contour_csv(const std::string& path, const CamDesignResult& result) {
  const std::vector<ContourPoint> points = contour_points(result);
  std::vector<std::vector<double>> columns(result.roller ? 5 : 3);
  for (const auto& p : points) {
    std::size_t c = 0;
    columns[c++].push_back(p.theta_rad / degree);
    if (result.roller) {
      columns[c++].push_back(p.pitch_x_m * 1e3);
      columns[c++].push_back(p.pitch_y_m * 1e3);
    }
    columns[c++].push_back(p.contour_x_m * 1e3);
    columns[c++].push_back(p.contour_y_m * 1e3);
  }
  if (result.roller)
    write_csv(path, {"theta_deg", "pitch_x_mm", "pitch_y_mm", "contour_x_mm", "contour_y_mm"}, columns);
  else
    write_csv(path, {"theta_deg", "contour_x_mm", "contour_y_mm"}, columns);
}

std::string contour_dxf(const std::vector<ContourPoint>& points) {
  std::string d;
  group(d, 0, "SECTION");
  group(d, 2, "HEADER");
  group(d, 9, "$ACADVER");
  group(d, 1, "AC1009");  // R12
  group(d, 9, "$INSUNITS");
  group(d, 70, "4");  // millimetres
  group(d, 0, "ENDSEC");
  group(d, 0, "SECTION");
  group(d, 2, "ENTITIES");
  // The shaft centre, so that the contour can be placed on the machine.
  group(d, 0, "POINT");
  group(d, 8, "CAM_CENTRE");
  group(d, 10, coordinate(0.0));
  group(d, 20, coordinate(0.0));
  group(d, 30, coordinate(0.0));
  group(d, 0, "POLYLINE");
  group(d, 8, "CAM_CONTOUR");
  group(d, 66, "1");  // vertices follow
  group(d, 10, coordinate(0.0));
  group(d, 20, coordinate(0.0));
  group(d, 30, coordinate(0.0));
  group(d, 70, "1");  // closed
  for (const auto& p : points) {
    group(d, 0, "VERTEX");
    group(d, 8, "CAM_CONTOUR");
    group(d, 10, coordinate(p.contour_x_m));
    group(d, 20, coordinate(p.contour_y_m));
    group(d, 30, coordinate(0.0));
  }
  group(d, 0, "SEQEND");
  group(d, 8, "CAM_CONTOUR");
  group(d, 0, "ENDSEC");
  group(d, 0, "EOF");
  return d;
}

void write_contour_dxf(const std::string& path, const CamDesignResult& result) {
  write_file_atomically(path, contour_dxf(contour_points(result)));
}

}  // namespace mechsim::tools::cam_design
