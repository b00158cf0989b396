// Minimal solvers in CONDITIONED coordinates (normalize.h): each builds its constraint matrix
// and solves it; the caller undoes the conditioning. They return no model on degeneracy
// instead of garbage.
//
// Quadratic: the paper's §4. Unknowns are the upper triangles of the symmetric Q_1..Q_3 with
// off-diagonal monomials doubled (eq 10): χ = (u², 2uv, 2u, v², 2v, 1), 18 unknowns, two rows
// per match: [χ, 0, -X χ] and [0, χ, -Y χ]. The tensor is the SVD null vector of the design
// matrix.
#pragma once

#include <Eigen/Core>

#include <array>
#include <optional>
#include <vector>

namespace artcam {

struct DltSolution {
  std::array<Eigen::Matrix3d, 3> q;   // quadratic: the tensors; linear models: lifted
  Eigen::Matrix3d h = Eigen::Matrix3d::Identity();  // linear models: target_from_source (column)
  bool linear = false;                // true: h is the model, q its lift
  Eigen::VectorXd singular_values;    // of the design matrix, ascending
  int null_dimension = 1;             // >1: the data do not determine the model
};

// Relative singular value below which a direction counts as null.
inline constexpr double kNullTolerance = 1e-9;

DltSolution solveQuadraticDlt(const std::vector<Eigen::Vector2d>& src,
                              const std::vector<Eigen::Vector2d>& dst);
DltSolution solveHomographyDlt(const std::vector<Eigen::Vector2d>& src,
                               const std::vector<Eigen::Vector2d>& dst);
DltSolution solveAffine(const std::vector<Eigen::Vector2d>& src,
                        const std::vector<Eigen::Vector2d>& dst);
DltSolution solveSimilarity(const std::vector<Eigen::Vector2d>& src,
                            const std::vector<Eigen::Vector2d>& dst);
DltSolution solveTranslation(const std::vector<Eigen::Vector2d>& src,
                             const std::vector<Eigen::Vector2d>& dst);

}  // namespace artcam
