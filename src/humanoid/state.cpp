#include "sims/humanoid/state.h"

namespace sims::humanoid {

void ReadPose(const Humanoid& h, const mjData* d, HumanoidPose* pose) {
  const double* q = d->qpos + h.root_qpos_adr();
  const double* v = d->qvel + h.root_qvel_adr();
  pose->root_pos = Eigen::Vector3d(q[0], q[1], q[2]);
  pose->root_rot = Eigen::Quaterniond(q[3], q[4], q[5], q[6]);
  pose->root_lin_vel = Eigen::Vector3d(v[0], v[1], v[2]);
  pose->root_ang_vel = pose->root_rot * Eigen::Vector3d(v[3], v[4], v[5]);
  for (int i = 0; i < kNumDofs; ++i) {
    pose->dof_pos[i] = d->qpos[h.dof_qpos_adr(i)];
    pose->dof_vel[i] = d->qvel[h.dof_qvel_adr(i)];
  }
}

void WritePose(const Humanoid& h, const HumanoidPose& pose, mjData* d) {
  double* q = d->qpos + h.root_qpos_adr();
  double* v = d->qvel + h.root_qvel_adr();
  const Eigen::Quaterniond r = pose.root_rot.normalized();
  q[0] = pose.root_pos.x();
  q[1] = pose.root_pos.y();
  q[2] = pose.root_pos.z();
  q[3] = r.w();
  q[4] = r.x();
  q[5] = r.y();
  q[6] = r.z();
  const Eigen::Vector3d w_local = r.conjugate() * pose.root_ang_vel;
  for (int k = 0; k < 3; ++k) {
    v[k] = pose.root_lin_vel[k];
    v[3 + k] = w_local[k];
  }
  for (int i = 0; i < kNumDofs; ++i) {
    d->qpos[h.dof_qpos_adr(i)] = pose.dof_pos[i];
    d->qvel[h.dof_qvel_adr(i)] = pose.dof_vel[i];
  }
}

void ReadBodyStates(const Humanoid& h, const mjData* d, BodyStates* bodies) {
  const mjModel* m = h.model();
  for (int b = 0; b < kNumBodies; ++b) {
    const int id = h.body_id(b);
    const double* p = d->xpos + 3 * id;
    const double* qq = d->xquat + 4 * id;
    bodies->pos[b] = Eigen::Vector3d(p[0], p[1], p[2]);
    bodies->rot[b] = Eigen::Quaterniond(qq[0], qq[1], qq[2], qq[3]);
    // cvel is the spatial velocity (ω, v) expressed at the subtree centre of mass of the
    // root; shift the linear part to the body origin: v_B = v_c + ω × (p_B − p_c).
    const double* cvel = d->cvel + 6 * id;
    const double* com = d->subtree_com + 3 * m->body_rootid[id];
    const Eigen::Vector3d w(cvel[0], cvel[1], cvel[2]);
    const Eigen::Vector3d vc(cvel[3], cvel[4], cvel[5]);
    const Eigen::Vector3d offset(p[0] - com[0], p[1] - com[1], p[2] - com[2]);
    bodies->ang_vel[b] = w;
    bodies->lin_vel[b] = vc + w.cross(offset);
  }
}

void ForwardKinematics(const Humanoid& h, const HumanoidPose& pose, mjData* scratch,
                       BodyStates* bodies) {
  const mjModel* m = h.model();
  WritePose(h, pose, scratch);
  mj_kinematics(m, scratch);
  mj_comPos(m, scratch);
  mj_comVel(m, scratch);
  ReadBodyStates(h, scratch, bodies);
}

Eigen::Vector3d ContactJointPosition(const BodyStates& bodies, int contact_joint) {
  const int b = ContactJointBodies()[contact_joint];
  return bodies.pos[b] + bodies.rot[b] * ContactJointOffset(contact_joint);
}

}  // namespace sims::humanoid
