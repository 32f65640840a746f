// The display level of detail (docs/viewer.md, "Level of detail"): while the plan plays, the page
// draws the original meshes simplified by meshoptimizer's simplifier (edge collapses under a
// quadric error bound, in WebAssembly), so that a software renderer keeps its frame rate; paused
// or stepping, it draws the originals.
import { MeshoptSimplifier } from 'meshoptimizer/simplifier';

// How far (metres) a simplified mesh may depart from the original surface: about a pixel of a
// whole scene drawn at the half resolution of software rendering while playing.
export const lodError = 0.003;

// Resolves when the simplifier's WebAssembly is compiled.
export const simplifierReady = MeshoptSimplifier.ready;

// The triangle indices of the simplified mesh, into the same positions (x y z per vertex, metres).
export function simplifiedIndices(positions, indices) {
  return MeshoptSimplifier.simplify(indices, positions, 3, 0, lodError, ['ErrorAbsolute'])[0];
}
