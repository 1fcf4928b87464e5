// A user's program on a system of bodies ((SE(3) x R^6)^k): dg_y's matrix is formed a pass of directions at a
// time, each direction's tangent made when its pass asks for it, and must equal dg_y along each basis direction
// alone, at a k whose directions take several passes (the last one short).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "core/groups/mechanics_groups.hpp"
#include "core/user_field/algebra_defect.hpp"
#include "core/user_field/program.hpp"
#include "core/user_field/user_vector_field.hpp"

namespace lienewton {
namespace {

// The masks of an algebra element's entries on the group's program matrix: the rotation parts' (skew) and the
// others' (translations, velocities).
struct Masks {
  Eigen::MatrixXd rotation, rest;
};
Masks algebra_masks(const SE3xR6PowerGroup& group) {
  const Eigen::MatrixXd all =
      program_matrix(group, group.hat(Eigen::VectorXd::Ones(group.dim()))).cwiseAbs().cwiseSign();
  Masks m{Eigen::MatrixXd::Zero(all.rows(), all.cols()), all};
  for (int b = 0; b < group.bodies(); ++b) {
    m.rotation.block(11 * b, 11 * b, 3, 3) = all.block(11 * b, 11 * b, 3, 3);
    m.rest.block(11 * b, 11 * b, 3, 3).setZero();
  }
  return m;
}

TEST(UserFieldBodies, DgMatrixInPassesEqualsEachDirectionAlone) {
  constexpr int k = 8;
  const SE3xR6PowerGroup group(k);
  const Masks masks = algebra_masks(group);
  // In the algebra body by body: the skew part of (y y) on the rotations, y y elsewhere on the algebra's entries.
  const auto program = user_field::compile("Y = y*y; g = S.*(Y - Y') + T.*sin(Y)", 11 * k,
                                           {{"S", masks.rotation}, {"T", masks.rest}});
  ASSERT_GT(program->directions_per_pass(group.dim()), 1);
  ASSERT_LT(program->directions_per_pass(group.dim()), group.dim() / 2);  // several passes
  ASSERT_NE(group.dim() % program->directions_per_pass(group.dim()), 0);  // the last one short
  const UserVectorField<SE3xR6PowerGroup> field(group, program);
  const SE3xR6PowerGroup::Element y = group.random(11);
  ASSERT_TRUE(field.g(y).allFinite());
  const Eigen::MatrixXd dg(field.dg_matrix(group, y));
  ASSERT_EQ(dg.rows(), group.dim());
  ASSERT_EQ(dg.cols(), group.dim());
  EXPECT_EQ(field.defect(), 0);
  double largest = 0;
  for (int i = 0; i < group.dim(); ++i) {
    const Eigen::VectorXd alone = field.dg(y, Eigen::VectorXd::Unit(group.dim(), i));
    EXPECT_LE((dg.col(i) - alone).norm(), 1e-13 * (1 + alone.norm())) << "direction " << i;
    largest = std::max(largest, alone.norm());
  }
  EXPECT_GT(largest, 0.1);  // the directions are not all trivial
}

}  // namespace
}  // namespace lienewton
