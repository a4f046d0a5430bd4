// The cam contour for manufacturing: a CSV table of the pitch curve and the real contour,
// and a minimal ASCII DXF (R12: HEADER with $INSUNITS = 4 (mm), ENTITIES with one closed
// POLYLINE of the real contour and a POINT at the shaft centre), in the cam-fixed frame
// of spec §2 (θ = 0 along +y), coordinates in mm.
#pragma once

#include <string>
#include <vector>

#include "cam_design_report.h"

namespace mechsim::tools::cam_design {

struct ContourPoint {
  double theta_rad;
  double pitch_x_m, pitch_y_m;      // roller centre (roller follower); NaN for a flat face
  double contour_x_m, contour_y_m;  // real cam contour
};

std::vector<ContourPoint> contour_points(const CamDesignResult& result);

// Columns theta_deg, pitch_x_mm, pitch_y_mm, contour_x_mm, contour_y_mm (a flat-faced
// follower has no pitch curve: those columns are left out). Throws std::runtime_error.
void write_contour_csv(const std::string& path, const CamDesignResult& result);

// The DXF text of a closed contour (points in m, written in mm), one "group code" line
// and one "value" line per pair.
std::string contour_dxf(const std::vector<ContourPoint>& points);
// Throws std::runtime_error naming the path.
void write_contour_dxf(const std::string& path, const CamDesignResult& result);

}  // namespace mechsim::tools::cam_design
