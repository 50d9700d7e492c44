#include "oracle/view_transform.hpp"

#include <algorithm>
#include <cmath>

namespace cullcheck::oracle {
namespace {

using Matrix3 = std::array<std::array<double, 3>, 3>;

Matrix3 product(const Matrix3& a, const Matrix3& b) {
  Matrix3 m{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) m[r][c] += a[r][k] * b[k][c];
  return m;
}

Matrix3 rotation_z(double a) { return {{{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}}}; }
Matrix3 rotation_x(double a) { return {{{1, 0, 0}, {0, std::cos(a), -std::sin(a)}, {0, std::sin(a), std::cos(a)}}}; }

// Columns: where eye x (right), y (up) and z (backward) point for the canonical camera, which
// looks along world +x with world +z up: right is world -y, up is world +z, backward world -x.
constexpr Matrix3 kCanonicalBase{{{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}};

// A relative widening of every plane in may_meet: the plane value is a sum of three products and
// a constant, each rounded once (relative error ~1e-16); 1e-9 of their magnitudes covers it.
constexpr double kRelativeSlack = 1e-9;

// The rotation part of `m` applied to the eye-space vector e.
Vec3 rotate(const Matrix4d& m, Vec3 e) {
  return {m[0][0] * e.x + m[0][1] * e.y + m[0][2] * e.z, m[1][0] * e.x + m[1][1] * e.y + m[1][2] * e.z,
          m[2][0] * e.x + m[2][1] * e.y + m[2][2] * e.z};
}

}  // namespace

ViewTransform::ViewTransform(const Camera& c)
    : eye_(c.position), orthographic_(c.orthographic()), omnidirectional_(c.omnidirectional()), near_(c.near), far_(c.far) {
  Matrix3 r{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  // The view volume of an omnidirectional camera is a ball: eye space is the world translated,
  // whatever the angles say.
  if (!omnidirectional_) r = product(product(rotation_z(c.yaw), kCanonicalBase), product(rotation_x(c.pitch), rotation_z(c.roll)));
  // view = [R^T | -R^T eye], its inverse [R | eye].
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) view_[i][j] = r[j][i], inverse_view_[i][j] = r[i][j];
    view_[i][3] = -(r[0][i] * eye_.x + r[1][i] * eye_.y + r[2][i] * eye_.z);
  }
  inverse_view_[0][3] = eye_.x, inverse_view_[1][3] = eye_.y, inverse_view_[2][3] = eye_.z;
  view_[3] = {0, 0, 0, 1};
  inverse_view_[3] = {0, 0, 0, 1};
  if (omnidirectional_) return;

  Matrix4d p{};
  if (orthographic_) {
    p[0] = {2.0 / c.ortho_width, 0, 0, 0};
    p[1] = {0, 2.0 / c.ortho_height, 0, 0};
    p[2] = {0, 0, -1, 0};  // depth in metres
    p[3] = {0, 0, 0, 1};
  } else {
    tan_h_ = std::tan(c.hfov / 2), tan_v_ = std::tan(c.vfov / 2);
    p[0] = {1.0 / tan_h_, 0, 0, 0};
    p[1] = {0, 1.0 / tan_v_, 0, 0};
    p[2] = {0, 0, -1, 0};  // depth in metres
    p[3] = {0, 0, -1, 0};  // w = depth: x / w is the image-plane coordinate
  }
  projection_ = p;

  // Rows of projection * view's rotation part (the translation is folded into p - eye): each
  // clip coordinate as a linear function of p - eye, plus the projection's constant column.
  Vec3 row[4];
  double constant[4];
  for (int i = 0; i < 4; ++i) {
    double v[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int j = 0; j < 3; ++j) v[j] += p[i][k] * view_[k][j];
    row[i] = {v[0], v[1], v[2]};
    constant[i] = p[i][3];
  }
  planes_[0] = {row[3] + row[0], constant[3] + constant[0]};  // w + x >= 0 (left)
  planes_[1] = {row[3] - row[0], constant[3] - constant[0]};  // w - x >= 0 (right)
  planes_[2] = {row[3] + row[1], constant[3] + constant[1]};  // w + y >= 0 (bottom)
  planes_[3] = {row[3] - row[1], constant[3] - constant[1]};  // w - y >= 0 (top)
  planes_[4] = {row[2], constant[2] - near_};                 // z - near >= 0
  planes_[5] = {row[2] * -1.0, far_ - constant[2]};           // far - z >= 0
}

Clip ViewTransform::clip(Vec3 p) const {
  const Vec3 q = p - eye_;
  double e[4];
  for (int i = 0; i < 3; ++i) e[i] = view_[i][0] * q.x + view_[i][1] * q.y + view_[i][2] * q.z;
  e[3] = 1.0;
  if (!projection_) return {e[0], e[1], e[2], 1.0};
  const Matrix4d& m = *projection_;
  double out[4];
  for (int i = 0; i < 4; ++i) out[i] = m[i][0] * e[0] + m[i][1] * e[1] + m[i][2] * e[2] + m[i][3] * e[3];
  return {out[0], out[1], out[2], out[3]};
}

bool ViewTransform::contains(Vec3 p) const {
  if (omnidirectional_) return length(p - eye_) <= far_;
  const Clip c = clip(p);
  return -c.w <= c.x && c.x <= c.w && -c.w <= c.y && c.y <= c.w && near_ <= c.z && c.z <= far_;
}

double distance_to_box(Vec3 eye, const Box3& box) {
  const double dx = std::max({box.lo.x - eye.x, 0.0, eye.x - box.hi.x});
  const double dy = std::max({box.lo.y - eye.y, 0.0, eye.y - box.hi.y});
  const double dz = std::max({box.lo.z - eye.z, 0.0, eye.z - box.hi.z});
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

bool ViewTransform::may_meet(const Box3& box, bool depth) const {
  if (omnidirectional_) return distance_to_box(eye_, box) <= far_ * (1.0 + kRelativeSlack);
  for (int i = 0; i < (depth ? 6 : 4); ++i) {
    const ClipPlane& f = planes_[i];
    // A linear function's maximum over a box is at the corner its gradient points to.
    const Vec3 corner{f.n.x >= 0 ? box.hi.x : box.lo.x, f.n.y >= 0 ? box.hi.y : box.lo.y, f.n.z >= 0 ? box.hi.z : box.lo.z};
    const Vec3 q = corner - eye_;
    const double value = f.n.x * q.x + f.n.y * q.y + f.n.z * q.z + f.d;
    const double magnitude = std::abs(f.n.x * q.x) + std::abs(f.n.y * q.y) + std::abs(f.n.z * q.z) + std::abs(f.d);
    if (value < -kRelativeSlack * magnitude) return false;
  }
  return true;
}

Vec3 ViewTransform::direction_through(double u, double v) const {
  // The projection's x, y and w rows act on eye space as the invertible diagonal-plus-z matrix
  // K = [[P00, 0, 0], [0, P11, 0], [0, 0, P32]]; K^-1 (u, v, 1) is the eye-space point at w = 1.
  const Matrix4d& p = *projection_;
  return normalized(rotate(inverse_view_, {u / p[0][0], v / p[1][1], 1.0 / p[3][2]}));
}

Vec3 ViewTransform::near_point_at(double u, double v) const {
  const Matrix4d& p = *projection_;
  return eye_ + rotate(inverse_view_, {u / p[0][0], v / p[1][1], -near_});  // eye space at depth near
}

}  // namespace cullcheck::oracle
