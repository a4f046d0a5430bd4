// The sweep's table (one row per point: point_row.h) as DIR/sweep.csv and the rows of
// DIR/sweep.json, and the plots made of it (DIR/plots/KEY.png).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "design.h"

namespace mechsim::sweep {

// The columns of the rows: the fixed ones first (point, the keys, outcome, reason, steps,
// wall time, worst errors), then every other column in the order the rows (by point) first
// have it. A column a row lacks is empty (CSV) or null (JSON).
std::vector<std::string> table_columns(const std::vector<VarySpec>& specs, const std::vector<nlohmann::json>& rows);

// Writes the rows under `columns` as CSV (RFC 4180 quoting; numbers as JSON writes them).
void write_table_csv(const std::string& path, const std::vector<std::string>& columns, const std::vector<nlohmann::json>& rows);

// One PNG per varied key with a number: the worst error and each report figure that changes
// over the sweep against the key (the points that ran to the end; a 2-key grid draws a line
// per value of the other key). Returns the files written; problems (no gnuplot) in `problems`.
std::vector<std::string> write_plots(const std::string& dir, const std::string& scene_name, const std::vector<VarySpec>& specs,
                                     const std::vector<std::string>& columns, const std::vector<nlohmann::json>& rows, bool grid,
                                     std::vector<std::string>* problems);

}  // namespace mechsim::sweep
