// The kaboum plan viewer (docs/viewer.md): reads the page's data, builds the scene, plays the run
// through the plan and exposes a small API on window.kaboum for scripts and tests.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GeometryLibrary, matrixPose, poseMatrix, readPageData, unpackGeometry } from './data.js';
import { RobotKinematics } from './kinematics.js';
import { simplifierReady } from './lod.js';
import { buildScene } from './scene.js';
import { buildRun, sampleRobot } from './timeline.js';
import { buildControls, listRun } from './ui.js';

// Whether WebGL runs on a software renderer (SwiftShader, llvmpipe): there the page draws without
// antialiasing, and at half resolution while playing, to keep its frame rate.
function softwareRendering() {
  const gl = document.createElement('canvas').getContext('webgl2');
  const info = gl && gl.getExtension('WEBGL_debug_renderer_info');
  const name = info ? String(gl.getParameter(info.UNMASKED_RENDERER_WEBGL)) : '';
  gl?.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|software/i.test(name);
}

async function start() {
  const data = readPageData();
  const library = new GeometryLibrary(await unpackGeometry(data.geometry));
  await simplifierReady;
  const controls = buildControls(data.title);
  const world = buildScene(data, library);
  const kinematics = data.robots.map((robot) => new RobotKinematics(robot));
  const configurations = data.robots.map((robot) => new Float64Array(robot.initial.length));
  const initialObjects = data.objects.map((object) => poseMatrix(object.pose));
  const grasped = data.objects.map(() => new THREE.Matrix4());
  const holders = new Array(data.objects.length);

  const software = softwareRendering();
  const renderer = new THREE.WebGLRenderer({ antialias: !software });
  renderer.setPixelRatio(window.devicePixelRatio);
  controls.view.append(renderer.domElement);
  const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 100);
  camera.up.set(0, 0, 1);
  const orbit = new OrbitControls(camera, renderer.domElement);

  const choices = new Map();
  let run = buildRun(data, choices);
  let items = [];
  let time = 0;
  let playing = false;
  let speed = 1;
  let frames = 0;

  // Robots at their configurations at `time`; objects replayed through the gripper events up to
  // it (a release by a robot not holding the object, the giver of a handover, changes nothing).
  function pose() {
    kinematics.forEach((robot, r) => {
      robot.update(sampleRobot(run, data, r, time, configurations[r]));
      robot.links.forEach((matrix, l) => world.robotLinks[r][l].matrix.copy(matrix));
    });
    holders.fill(null);
    data.objects.forEach((_, o) => world.objects[o].matrix.copy(initialObjects[o]));
    for (const event of run.events) {
      if (event.time > time) break;
      if (event.kind === 'grasp') {
        holders[event.object] = event;
        poseMatrix(event.pose, grasped[event.object]);
      } else if (holders[event.object] && holders[event.object].robot === event.robot) {
        holders[event.object] = null;
        poseMatrix(event.pose, world.objects[event.object].matrix);
      }
    }
    holders.forEach((holder, o) => {
      if (holder) {
        world.objects[o].matrix.multiplyMatrices(
          kinematics[holder.robot].links[holder.link],
          grasped[o],
        );
      }
    });
    world.scene.updateMatrixWorld(true);
    controls.timeline.value = run.duration > 0 ? time / run.duration : 0;
    controls.time.textContent = `${time.toFixed(2)} / ${run.duration.toFixed(2)} s`;
    items.forEach((item, i) => {
      const action = run.actions[i];
      item.classList.toggle('current', action.start <= time && time < action.end);
    });
  }

  function seek(t) {
    time = Math.min(Math.max(Number(t) || 0, 0), run.duration);
    pose();
  }

  function relist() {
    items = listRun(controls.actions, run, seek, (node, value) => chooseBranch(node, value));
  }

  function chooseBranch(node, value) {
    if (data.nodes[node]?.kind !== 'branch') throw new Error(`node ${node} is no sensing branch`);
    choices.set(node, Boolean(value));
    run = buildRun(data, choices);
    relist();
    seek(time);
  }

  function setPlaying(on) {
    playing = on;
    if (playing && time >= run.duration) time = 0;
    if (software) renderer.setPixelRatio(window.devicePixelRatio * (playing ? 0.5 : 1));
    world.simplify(playing);
    controls.play.textContent = playing ? 'Pause' : 'Play';
  }

  controls.play.addEventListener('click', () => setPlaying(!playing));
  window.addEventListener('keydown', (event) => {
    if (event.code !== 'Space' || event.target.closest('select, input, button')) return;
    event.preventDefault();
    setPlaying(!playing);
  });
  controls.speed.addEventListener('change', () => (speed = Number(controls.speed.value)));
  controls.timeline.addEventListener('input', () => {
    seek(Number(controls.timeline.value) * run.duration);
  });
  controls.pieces.addEventListener('change', () => world.showPieces(controls.pieces.checked));
  controls.locations.addEventListener('change', () => {
    world.locations.visible = controls.locations.checked;
  });

  function frame() {
    const box = new THREE.Box3().setFromObject(world.scene);
    const centre = box.getCenter(new THREE.Vector3());
    const radius = Math.max(box.getSize(new THREE.Vector3()).length() / 2, 0.1);
    orbit.target.copy(centre);
    camera.position.copy(centre).add(new THREE.Vector3(1.2, -1.6, 1.0).multiplyScalar(radius));
    camera.near = radius / 100;
    camera.far = radius * 20;
    orbit.update();
  }

  function resize() {
    const { clientWidth: width, clientHeight: height } = controls.view;
    renderer.setSize(width, height, false);
    camera.aspect = width / Math.max(height, 1);
    camera.updateProjectionMatrix();
  }
  window.addEventListener('resize', resize);

  let last = performance.now();
  function animate(now) {
    const dt = (now - last) / 1000;
    last = now;
    if (playing) {
      time += dt * speed;
      if (time >= run.duration) {
        time = run.duration;
        setPlaying(false);
      }
      pose();
    }
    orbit.update();
    renderer.render(world.scene, camera);
    ++frames;
    requestAnimationFrame(animate);
  }

  relist();
  pose();
  frame();
  resize();
  renderer.render(world.scene, camera);
  requestAnimationFrame(animate);

  window.kaboum = {
    ready: true,
    duration: () => run.duration,
    time: () => time,
    seek,
    play: () => setPlaying(true),
    pause: () => setPlaying(false),
    setSpeed: (value) => (speed = Number(value)),
    frames: () => frames,
    triangles: () => renderer.info.render.triangles,
    actions: () => run.actions.map(({ node, name, start, end }) => ({ node, name, start, end })),
    branches: () =>
      run.branches.map(({ node, test, value, time: at }) => ({ node, test, value, time: at })),
    branch: chooseBranch,
    showPieces: (on) => {
      controls.pieces.checked = Boolean(on);
      world.showPieces(Boolean(on));
    },
    linkPoses: () => {
      const out = {};
      data.robots.forEach((robot, r) => {
        out[robot.name] = {};
        robot.links.forEach((link, l) => {
          out[robot.name][link.name] = matrixPose(kinematics[r].links[l]);
        });
      });
      return out;
    },
    objectPoses: () => {
      const out = {};
      data.objects.forEach((object, o) => (out[object.name] = matrixPose(world.objects[o].matrix)));
      return out;
    },
  };
}

window.kaboum = { ready: false };
start().catch((error) => {
  console.error(`kaboum viewer: ${error.stack || error}`);
  window.kaboum = { ready: false, error: String(error) };
});
