// The three.js scene of a page: robots (a group per link holding its original shapes and its
// convex pieces), objects (which follow the robot links holding them) and location regions; every
// original mesh with its simplified geometry beside it, drawn while the plan plays (lod.js).
import * as THREE from 'three';
import { ConvexGeometry } from 'three/addons/geometries/ConvexGeometry.js';
import { poseMatrix } from './data.js';

const materials = {
  robot: new THREE.MeshLambertMaterial({ color: 0xe0a040, flatShading: true }),
  movable: new THREE.MeshLambertMaterial({ color: 0x3f7fd0, flatShading: true }),
  fixed: new THREE.MeshLambertMaterial({ color: 0xa0a0a0, flatShading: true }),
  location: new THREE.MeshBasicMaterial({
    color: 0x40c060,
    transparent: true,
    opacity: 0.18,
    depthWrite: false,
  }),
  support: new THREE.MeshBasicMaterial({
    color: 0xd0c040,
    transparent: true,
    opacity: 0.18,
    depthWrite: false,
  }),
};

// Convex pieces in a few colours so that neighbouring pieces can be told apart.
const pieceMaterials = [0xe05050, 0x50b050, 0x5070e0, 0xd0a030, 0xa050c0, 0x40b0b0].map(
  (color) =>
    new THREE.MeshLambertMaterial({ color, flatShading: true, transparent: true, opacity: 0.85 }),
);

function shapeGeometry(shape, library) {
  if (shape.box) return new THREE.BoxGeometry(...shape.box);
  if (shape.sphere !== undefined) return new THREE.SphereGeometry(shape.sphere, 24, 16);
  if (shape.cylinder) {
    const [radius, length] = shape.cylinder;
    // three.js cylinders run along y; URDF cylinders along z.
    return new THREE.CylinderGeometry(radius, radius, length, 24).rotateX(Math.PI / 2);
  }
  return library.geometry(shape.mesh);
}

// Adds the shapes to `group`; each mesh shape's three.js mesh, original geometry and simplified
// geometry to `levels`.
function addShapes(group, shapes, material, library, levels) {
  for (const shape of shapes) {
    const mesh = new THREE.Mesh(shapeGeometry(shape, library), material);
    mesh.matrixAutoUpdate = false;
    mesh.matrix.copy(poseMatrix(shape.origin));
    group.add(mesh);
    if (shape.mesh !== undefined) {
      levels.push({ mesh, original: mesh.geometry, simplified: library.simplified(shape.mesh) });
    }
  }
}

function addPieces(group, entries, library, origin) {
  for (const entry of entries) {
    const mesh = new THREE.Mesh(
      library.geometry(entry),
      pieceMaterials[entry % pieceMaterials.length],
    );
    mesh.matrixAutoUpdate = false;
    if (origin) mesh.matrix.copy(origin);
    group.add(mesh);
  }
}

// A body's two looks: its original shapes and its convex pieces, one shown at a time.
function bodyGroup(name) {
  const group = new THREE.Group();
  group.name = name;
  group.matrixAutoUpdate = false;
  const original = new THREE.Group();
  const pieces = new THREE.Group();
  pieces.visible = false;
  group.add(original, pieces);
  return { group, original, pieces };
}

function locationMesh(location) {
  const material = location.support ? materials.support : materials.location;
  let geometry;
  if (location.box) {
    const [lower, upper] = location.box;
    const size = upper.map((u, i) => Math.max(u - lower[i], 1e-3));
    geometry = new THREE.BoxGeometry(...size).translate(
      ...upper.map((u, i) => (u + lower[i]) / 2),
    );
  } else {
    geometry = new ConvexGeometry(location.hull.map((p) => new THREE.Vector3(...p)));
  }
  const mesh = new THREE.Mesh(geometry, material);
  mesh.name = location.name;
  mesh.matrixAutoUpdate = false;
  mesh.matrix.copy(poseMatrix(location.pose));
  return mesh;
}

export function buildScene(data, library) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0xf4f4f0);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x606060, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(2, -3, 5);
  scene.add(sun);

  const looks = [];
  const levels = [];
  const robotLinks = data.robots.map((robot) =>
    robot.links.map((link) => {
      const body = bodyGroup(link.name);
      addShapes(body.original, link.shapes, materials.robot, library, levels);
      for (const part of link.pieces) {
        addPieces(body.pieces, part.entries, library, poseMatrix(part.origin));
      }
      scene.add(body.group);
      looks.push(body);
      return body.group;
    }),
  );
  const objects = data.objects.map((object) => {
    const body = bodyGroup(object.name);
    addShapes(
      body.original,
      object.shapes,
      object.movable ? materials.movable : materials.fixed,
      library,
      levels,
    );
    addPieces(body.pieces, object.pieces, library, null);
    body.group.matrix.copy(poseMatrix(object.pose));
    scene.add(body.group);
    looks.push(body);
    return body.group;
  });
  const locations = new THREE.Group();
  for (const location of data.locations) locations.add(locationMesh(location));
  scene.add(locations);

  return {
    scene,
    robotLinks,
    objects,
    locations,
    showPieces(on) {
      for (const look of looks) {
        look.original.visible = !on;
        look.pieces.visible = on;
      }
    },
    // The original meshes simplified (`true`, while playing) or as they are.
    simplify(on) {
      for (const level of levels) level.mesh.geometry = on ? level.simplified : level.original;
    },
  };
}
