// CSV inputs of the CLI (DESIGN §5): match lists with the header `src_x,src_y,dst_x,dst_y`
// (pixels; 3D: src_x,src_y,src_z,dst_x,dst_y,dst_z), and point lists `x,y` (a header line is
// allowed). Errors name the file, the line and the cause.
#pragma once

#include "core/model/fit_record.h"
#include "core/model/status.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace artcam {

// dimension 2 or 3: coordinates per side.
Result<std::vector<PointMatch>> readMatchesCsv(const std::string& path, int dimension = 2);
Result<std::vector<Eigen::Vector2d>> readPointsCsv(const std::string& path);
// Writes the header and rows with %.17g numbers (atomic).
Status writeMatchesCsv(const std::string& path, const std::vector<PointMatch>& matches);

}  // namespace artcam
