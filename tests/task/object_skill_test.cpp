#include "sims/task/object_skill.h"

#include <gtest/gtest.h>

#include "sims/scene/builtin.h"
#include "sims/scene/height_grid.h"

namespace sims::task {
namespace {

// Parts are looked up by the names the skills bind to; every part is described, so a skill
// binding to a kind of part no built-in skill uses (a table top) finds it too.
TEST(ObjectGeometryTest, DescribesEveryPartByName) {
  scene::Scene s;
  s.objects.push_back(scene::MakeFurniture("bed", scene::DefaultFurnitureParams("bed")));
  s.objects.push_back(scene::MakeFurniture("table", scene::DefaultFurnitureParams("table")));
  scene::PlaceObject(&s.objects[0], 0, 0, 0.5);
  scene::PlaceObject(&s.objects[1], 4, 0, 0);
  const scene::SceneHeightGrid grid(s);

  const ObjectGeometry bed = DescribeObject(s, 0, grid);
  ASSERT_EQ(bed.parts.size(), s.objects[0].parts.size());
  for (size_t k = 0; k < bed.parts.size(); ++k) {
    EXPECT_EQ(bed.parts[k].index, static_cast<int>(k));
    EXPECT_EQ(bed.parts[k].name, s.objects[0].parts[k].name);
  }
  ASSERT_NE(bed.part(kMattressPart), nullptr);
  EXPECT_EQ(bed.part(kSeatPart), nullptr);
  EXPECT_EQ(bed.part_index(kSeatPart), -1);
  const int mattress = bed.part_index(kMattressPart);
  EXPECT_EQ(s.objects[0].parts[mattress].name, "mattress");
  int pillows = 0;
  for (const auto& p : s.objects[0].parts) pillows += p.name == "pillow";
  EXPECT_GT(pillows, 0);
  EXPECT_EQ(static_cast<int>(bed.part_indices("pillow").size()), pillows);
  // The local bounds are the part's vertices in the object frame (the bed is turned by 0.5).
  const scene::Aabb& m = bed.part_local(kMattressPart);
  for (const auto& v : s.objects[0].parts[mattress].mesh.vertices) {
    const Eigen::Vector3d v_O = bed.X_WO.inverse() * v;
    EXPECT_TRUE((v_O.array() >= m.min.array() - 1e-9).all() &&
                (v_O.array() <= m.max.array() + 1e-9).all());
  }
  EXPECT_GT(m.max.z(), 0.3);

  const ObjectGeometry table = DescribeObject(s, 1, grid);
  ASSERT_NE(table.part("top"), nullptr);
  EXPECT_NEAR(table.part_local("top").max.z(),
              s.objects[1].parts[table.part_index("top")].mesh.Bounds().max.z(), 1e-9);
}

}  // namespace
}  // namespace sims::task
