#include "io/shapes.h"

#include <cmath>

#include <mujoco/mujoco.h>
#include <Eigen/Geometry>

namespace sims::io {

namespace {

using Eigen::Vector3d;

// Rings of a capsule along z (half length h, radius r): a sphere split at the equator with
// the halves moved apart; radii (ex, ey, ez) scale an ellipsoid (h = 0).
void AddRoundShape(double r, double h, const Vector3d& radii_scale, int segments,
                   const Eigen::Isometry3d& X, ShapeMesh* out) {
  const int rings = std::max(2, segments / 4);
  std::vector<std::pair<double, double>> lat;  // (polar angle, z offset)
  for (int i = 0; i <= rings; ++i) lat.push_back({0.5 * M_PI * i / rings, h});
  for (int i = 0; i <= rings; ++i) lat.push_back({0.5 * M_PI + 0.5 * M_PI * i / rings, -h});
  const uint32_t base = out->num_vertices();
  const Eigen::Matrix3d R = X.linear();
  for (const auto& [theta, z] : lat) {
    for (int s = 0; s <= segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      const Vector3d n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                       std::cos(theta));
      const Vector3d p = r * n.cwiseProduct(radii_scale) + Vector3d(0, 0, z);
      // Normals of a scaled sphere scale inversely.
      const Vector3d nn = n.cwiseQuotient(radii_scale).normalized();
      out->AddVertex(X * p, R * nn);
    }
  }
  const int cols = segments + 1;
  for (int i = 0; i + 1 < static_cast<int>(lat.size()); ++i) {
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = base + i * cols + s, b = a + 1, c = a + cols, d = c + 1;
      out->indices.insert(out->indices.end(), {a, c, b, b, c, d});
    }
  }
}

void AddCylinder(double r, double h, int segments, const Eigen::Isometry3d& X, ShapeMesh* out) {
  const Eigen::Matrix3d R = X.linear();
  const uint32_t base = out->num_vertices();
  for (int s = 0; s <= segments; ++s) {
    const double phi = 2 * M_PI * s / segments;
    const Vector3d n(std::cos(phi), std::sin(phi), 0);
    out->AddVertex(X * (r * n + Vector3d(0, 0, -h)), R * n);
    out->AddVertex(X * (r * n + Vector3d(0, 0, h)), R * n);
  }
  for (int s = 0; s < segments; ++s) {
    const uint32_t a = base + 2 * s, b = a + 1, c = a + 2, d = a + 3;
    out->indices.insert(out->indices.end(), {a, c, b, b, c, d});
  }
  for (int side : {-1, 1}) {
    const Vector3d n(0, 0, side);
    const uint32_t centre = out->AddVertex(X * Vector3d(0, 0, side * h), R * n);
    for (int s = 0; s <= segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      out->AddVertex(X * Vector3d(r * std::cos(phi), r * std::sin(phi), side * h), R * n);
    }
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = centre + 1 + s, b = a + 1;
      if (side > 0)
        out->indices.insert(out->indices.end(), {centre, a, b});
      else
        out->indices.insert(out->indices.end(), {centre, b, a});
    }
  }
}

void AddBox(const Vector3d& half, const Eigen::Isometry3d& X, ShapeMesh* out) {
  const Eigen::Matrix3d R = X.linear();
  for (int axis = 0; axis < 3; ++axis) {
    for (int side : {-1, 1}) {
      Vector3d n = Vector3d::Zero();
      n[axis] = side;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const uint32_t base = out->num_vertices();
      for (int k = 0; k < 4; ++k) {
        Vector3d p;
        p[axis] = side * half[axis];
        p[u] = ((k == 1 || k == 2) ? 1 : -1) * half[u];
        p[v] = (k >= 2 ? 1 : -1) * half[v];
        out->AddVertex(X * p, R * n);
      }
      // (u, v) × order gives +axis normals for side = +1; flip winding otherwise.
      if (side > 0)
        out->indices.insert(out->indices.end(),
                            {base, base + 1, base + 2, base, base + 2, base + 3});
      else
        out->indices.insert(out->indices.end(),
                            {base, base + 2, base + 1, base, base + 3, base + 2});
    }
  }
}

}  // namespace

uint32_t ShapeMesh::AddVertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  for (int k = 0; k < 3; ++k) {
    positions.push_back(static_cast<float>(p[k]));
    normals.push_back(static_cast<float>(n[k]));
  }
  return num_vertices() - 1;
}

std::array<ShapeMesh, humanoid::kNumBodies> HumanoidBodyShapes(const humanoid::Humanoid& humanoid,
                                                               int segments) {
  std::array<ShapeMesh, humanoid::kNumBodies> out;
  const mjModel* m = humanoid.model();
  segments = std::max(6, segments);
  for (int g = 0; g < m->ngeom; ++g) {
    const int b = humanoid.geom_body(g);
    if (b < 0) continue;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Vector3d(m->geom_pos[3 * g], m->geom_pos[3 * g + 1], m->geom_pos[3 * g + 2]);
    X.linear() = Eigen::Quaterniond(m->geom_quat[4 * g], m->geom_quat[4 * g + 1],
                                    m->geom_quat[4 * g + 2], m->geom_quat[4 * g + 3])
                     .normalized()
                     .toRotationMatrix();
    const double* size = m->geom_size + 3 * g;
    switch (m->geom_type[g]) {
      case mjGEOM_SPHERE:
        AddRoundShape(size[0], 0, Vector3d::Ones(), segments, X, &out[b]);
        break;
      case mjGEOM_CAPSULE:
        AddRoundShape(size[0], size[1], Vector3d::Ones(), segments, X, &out[b]);
        break;
      case mjGEOM_ELLIPSOID:
        AddRoundShape(1.0, 0, Vector3d(size[0], size[1], size[2]), segments, X, &out[b]);
        break;
      case mjGEOM_CYLINDER:
        AddCylinder(size[0], size[1], segments, X, &out[b]);
        break;
      case mjGEOM_BOX:
        AddBox(Vector3d(size[0], size[1], size[2]), X, &out[b]);
        break;
      default:
        break;  // meshes and planes do not occur on the humanoid
    }
  }
  return out;
}

ShapeMesh FlatShadedMesh(const scene::TriangleMesh& mesh) {
  ShapeMesh out;
  out.positions.reserve(mesh.triangles.size() * 9);
  out.normals.reserve(mesh.triangles.size() * 9);
  out.indices.reserve(mesh.triangles.size() * 3);
  for (int t = 0; t < static_cast<int>(mesh.triangles.size()); ++t) {
    const Vector3d n = mesh.TriangleNormal(t);
    if (n.squaredNorm() < 0.5) continue;
    for (int k = 0; k < 3; ++k)
      out.indices.push_back(out.AddVertex(mesh.vertices[mesh.triangles[t][k]], n));
  }
  return out;
}

ShapeMesh FloorQuad(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  ShapeMesh out;
  const Vector3d up(0, 0, 1);
  out.AddVertex(Vector3d(lo.x(), lo.y(), 0), up);
  out.AddVertex(Vector3d(hi.x(), lo.y(), 0), up);
  out.AddVertex(Vector3d(hi.x(), hi.y(), 0), up);
  out.AddVertex(Vector3d(lo.x(), hi.y(), 0), up);
  out.indices = {0, 1, 2, 0, 2, 3};
  return out;
}

}  // namespace sims::io
