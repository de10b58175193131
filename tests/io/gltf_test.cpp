#include "sims/io/gltf_export.h"

#include <gtest/gtest.h>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>
#include <fstream>
#include <functional>
#include <map>

#include "common/test_util.h"
#include "io/io_test_util.h"
#include "sims/core/error.h"
#include "sims/motion/retarget.h"
#include "sims/motion/skeleton.h"

namespace sims::io {
namespace {

struct Imported {
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  std::map<std::string, const aiNode*> nodes;
  int node_count = 0;
};

void Import(const std::filesystem::path& path, Imported* out) {
  out->scene = out->importer.ReadFile(path.string(), aiProcess_ValidateDataStructure);
  ASSERT_NE(out->scene, nullptr) << out->importer.GetErrorString();
  std::function<void(const aiNode*)> walk = [&](const aiNode* n) {
    ++out->node_count;
    out->nodes[n->mName.C_Str()] = n;
    for (unsigned i = 0; i < n->mNumChildren; ++i) walk(n->mChildren[i]);
  };
  walk(out->scene->mRootNode);
}

// Nodes the exporter must write: world, 15 bodies, scene, objects, parts, floor.
int ExpectedNodes(const scene::Scene& s) {
  int n = 1 + humanoid::kNumBodies + 1 + 1;
  for (const auto& o : s.objects) n += 1 + static_cast<int>(o.parts.size());
  if (!s.walls.empty()) n += 1;
  return n;
}

TEST(GltfTest, GlbReimportsWithBvhSkeletonAndAnimation) {
  const MotionRecord rec = testing::TestRecord(1.0);
  const scene::Scene scene = testing::TestScene();
  const auto dir = sims::testing::TempDir("io_gltf");
  const auto glb = dir / "scene.glb";
  ExportGltf(rec, &scene, glb);

  Imported imp;
  ASSERT_NO_FATAL_FAILURE(Import(glb, &imp));
  EXPECT_EQ(imp.node_count, ExpectedNodes(scene));

  // The character hierarchy is the BVH's: same names, same parents.
  const motion::BvhMotion bvh =
      motion::HumanoidClipToBvh(RecordToClip(rec), motion::HumanoidSkeleton::Default());
  ASSERT_EQ(bvh.joints.size(), static_cast<std::size_t>(humanoid::kNumBodies));
  for (const auto& j : bvh.joints) {
    ASSERT_TRUE(imp.nodes.count(j.name)) << "no node " << j.name;
    const aiNode* n = imp.nodes[j.name];
    const std::string parent = n->mParent ? n->mParent->mName.C_Str() : "";
    EXPECT_EQ(parent, j.parent < 0 ? "sims_world" : bvh.joints[j.parent].name) << j.name;
    EXPECT_GT(n->mNumMeshes, 0u) << j.name << " has no shape";
  }
  for (const auto& o : scene.objects) EXPECT_TRUE(imp.nodes.count(o.instance)) << o.instance;

  ASSERT_EQ(imp.scene->mNumAnimations, 1u);
  const aiAnimation* anim = imp.scene->mAnimations[0];
  const double tps = anim->mTicksPerSecond > 0 ? anim->mTicksPerSecond : 1.0;
  EXPECT_NEAR(anim->mDuration / tps, rec.duration(), 1e-3);
  EXPECT_EQ(anim->mNumChannels, static_cast<unsigned>(humanoid::kNumBodies));
  for (unsigned c = 0; c < anim->mNumChannels; ++c) {
    const aiNodeAnim* ch = anim->mChannels[c];
    EXPECT_EQ(ch->mNumRotationKeys, static_cast<unsigned>(rec.num_frames()));
    if (std::string(ch->mNodeName.C_Str()) == "pelvis") {
      ASSERT_EQ(ch->mNumPositionKeys, static_cast<unsigned>(rec.num_frames()));
      const int f = rec.num_frames() - 1;
      const aiVector3D p = ch->mPositionKeys[f].mValue;
      EXPECT_NEAR(p.x, rec.frames[f].root_pos.x(), 1e-4);
      EXPECT_NEAR(p.y, rec.frames[f].root_pos.y(), 1e-4);
      EXPECT_NEAR(p.z, rec.frames[f].root_pos.z(), 1e-4);
    }
  }

  // World transform of a hand at the last frame (the animation's last keys applied through the
  // node tree) equals the recorded body pose (project Z-up: undo the world node's rotation).
  std::map<std::string, aiMatrix4x4> local;
  for (unsigned c = 0; c < anim->mNumChannels; ++c) {
    const aiNodeAnim* ch = anim->mChannels[c];
    const aiQuaternion q = ch->mRotationKeys[ch->mNumRotationKeys - 1].mValue;
    aiVector3D t = imp.nodes[ch->mNodeName.C_Str()]->mTransformation * aiVector3D(0, 0, 0);
    if (ch->mNumPositionKeys > 0) t = ch->mPositionKeys[ch->mNumPositionKeys - 1].mValue;
    local[ch->mNodeName.C_Str()] = aiMatrix4x4(aiVector3D(1, 1, 1), q, t);
  }
  const int hand = humanoid::kLeftHand;
  aiMatrix4x4 X;
  for (const aiNode* n = imp.nodes[humanoid::BodyNames()[hand]];
       n && n->mName != aiString("sims_world"); n = n->mParent)
    X = local[n->mName.C_Str()] * X;
  const aiVector3D p = X * aiVector3D(0, 0, 0);
  const Eigen::Vector3d& want = rec.frames.back().body_pos[hand];
  EXPECT_NEAR(p.x, want.x(), 2e-3);
  EXPECT_NEAR(p.y, want.y(), 2e-3);
  EXPECT_NEAR(p.z, want.z(), 2e-3);
}

TEST(GltfTest, GltfWithBinSidecarAndCharacterOnly) {
  const MotionRecord rec = testing::TestRecord(0.5);
  const auto dir = sims::testing::TempDir("io_gltf2");
  ExportGltf(rec, nullptr, dir / "motion.gltf");
  EXPECT_TRUE(std::filesystem::exists(dir / "motion.bin"));
  Imported imp;
  ASSERT_NO_FATAL_FAILURE(Import(dir / "motion.gltf", &imp));
  EXPECT_EQ(imp.node_count, 1 + humanoid::kNumBodies + 1);  // world, bodies, floor
  ASSERT_EQ(imp.scene->mNumAnimations, 1u);
  const aiAnimation* anim = imp.scene->mAnimations[0];
  EXPECT_NEAR(anim->mDuration / anim->mTicksPerSecond, rec.duration(), 1e-3);
}

TEST(GltfTest, RejectsUnknownExtension) {
  const auto dir = sims::testing::TempDir("io_gltf3");
  try {
    ExportGltf(testing::TestRecord(0.2), nullptr, dir / "x.obj");
    FAIL() << "accepted .obj";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(".glb or .gltf"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sims::io
