// The page's data (docs/viewer.md, "Page data"): the JSON that `kaboum view` writes into the page,
// and its packed geometry inflated into three.js buffer geometries.
import * as THREE from 'three';
import { ConvexGeometry } from 'three/addons/geometries/ConvexGeometry.js';
import { simplifiedIndices } from './lod.js';

export function readPageData() {
  const element = document.getElementById('kaboum-data');
  if (!element) throw new Error('the page holds no kaboum-data element');
  return JSON.parse(element.textContent);
}

async function inflate(base64) {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('deflate'));
  return new Uint8Array(await new Response(stream).arrayBuffer());
}

// Every entry of the pack as its positions (Float32Array, x y z) and indices (Uint32Array or
// null for a convex piece's vertices).
export async function unpackGeometry(pack) {
  const positionBytes = await inflate(pack.positions);
  const indexBytes = await inflate(pack.indices);
  const quantized = new Uint16Array(positionBytes.buffer, 0, positionBytes.length / 2);
  const indices = new Uint32Array(indexBytes.buffer, 0, indexBytes.length / 4);
  return pack.entries.map((entry) => {
    const [first, count] = entry.positions;
    const positions = new Float32Array(count * 3);
    for (let i = 0; i < count * 3; ++i) {
      const axis = i % 3;
      positions[i] = entry.min[axis] + quantized[first * 3 + i] * entry.step[axis];
    }
    const [indexFirst, indexCount] = entry.indices;
    return {
      positions,
      indices: indexCount > 0 ? indices.slice(indexFirst, indexFirst + indexCount) : null,
    };
  });
}

// A buffer geometry per entry, made on first use: the mesh, or the convex hull of the points; and
// a mesh's simplified geometry (lod.js), which shares the mesh's vertices.
export class GeometryLibrary {
  constructor(entries) {
    this.entries = entries;
    this.cache = new Map();
    this.simplifiedCache = new Map();
  }

  // The mesh of entry `index` simplified (lod.js): its own triangles over the mesh's vertices.
  simplified(index) {
    let geometry = this.simplifiedCache.get(index);
    if (geometry) return geometry;
    const original = this.geometry(index);
    const entry = this.entries[index];
    geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', original.getAttribute('position'));
    geometry.setAttribute('normal', original.getAttribute('normal'));
    geometry.setIndex(
      new THREE.BufferAttribute(simplifiedIndices(entry.positions, entry.indices), 1),
    );
    this.simplifiedCache.set(index, geometry);
    return geometry;
  }

  geometry(index) {
    let geometry = this.cache.get(index);
    if (geometry) return geometry;
    const entry = this.entries[index];
    if (entry.indices) {
      geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.BufferAttribute(entry.positions, 3));
      geometry.setIndex(new THREE.BufferAttribute(entry.indices, 1));
    } else {
      const points = [];
      for (let i = 0; i < entry.positions.length; i += 3) {
        points.push(
          new THREE.Vector3(entry.positions[i], entry.positions[i + 1], entry.positions[i + 2]),
        );
      }
      geometry = new ConvexGeometry(points);
    }
    geometry.computeVertexNormals();
    this.cache.set(index, geometry);
    return geometry;
  }
}

// A pose of the plan file ({position, quaternion_wxyz}) as a matrix.
export function poseMatrix(pose, out = new THREE.Matrix4()) {
  const [w, x, y, z] = pose.quaternion_wxyz;
  return out.compose(
    new THREE.Vector3(...pose.position),
    new THREE.Quaternion(x, y, z, w),
    new THREE.Vector3(1, 1, 1),
  );
}

const scratchPosition = new THREE.Vector3();
const scratchRotation = new THREE.Quaternion();
const scratchScale = new THREE.Vector3();

// A matrix as a pose of the plan file.
export function matrixPose(matrix) {
  matrix.decompose(scratchPosition, scratchRotation, scratchScale);
  return {
    position: scratchPosition.toArray(),
    quaternion_wxyz: [scratchRotation.w, scratchRotation.x, scratchRotation.y, scratchRotation.z],
  };
}
