// Forward kinematics of the page's robots (as kinematics::RobotModel::linkPoses, thesis §3.1):
// joints parent-first, each child frame = parent frame * joint origin * the joint's motion.
import * as THREE from 'three';
import { poseMatrix } from './data.js';

export class RobotKinematics {
  constructor(robot) {
    this.base = poseMatrix(robot.base);
    this.joints = robot.joints.map((joint) => ({
      ...joint,
      originMatrix: poseMatrix(joint.origin),
      axisVector: new THREE.Vector3(...joint.axis),
    }));
    this.links = robot.links.map(() => new THREE.Matrix4());
    this.motion = new THREE.Matrix4();
  }

  // Every link's world matrix at configuration q into this.links. Allocates nothing.
  update(q) {
    this.links[0].copy(this.base);
    for (const joint of this.joints) {
      const value = joint.variable >= 0 ? q[joint.variable] : 0;
      if (joint.type === 'revolute') {
        this.motion.makeRotationAxis(joint.axisVector, value);
      } else if (joint.type === 'prismatic') {
        this.motion.makeTranslation(
          joint.axisVector.x * value,
          joint.axisVector.y * value,
          joint.axisVector.z * value,
        );
      } else {
        this.motion.identity();
      }
      this.links[joint.child]
        .multiplyMatrices(this.links[joint.parent], joint.originMatrix)
        .multiply(this.motion);
    }
    return this.links;
  }
}
