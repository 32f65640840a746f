// One run through the plan (thesis §6.1.3, branched execution): from the root, each sensing
// branch taking the outcome chosen for it (true unless chosen otherwise), the actions one after
// another on one clock, each motion timed as `kaboum execute` times it (rest-to-rest quintics
// through the certified waypoints, exec::TimedPath) and gripper events at their instants.
export function buildRun(data, choices) {
  const run = { duration: 0, actions: [], branches: [], motionsOf: [], events: [] };
  for (let r = 0; r < data.robots.length; ++r) run.motionsOf.push([]);
  let time = 0;
  let n = data.root;
  for (let guard = 0; n >= 0 && guard <= data.nodes.length; ++guard) {
    const node = data.nodes[n];
    if (node.kind === 'goal') break;
    if (node.kind === 'branch') {
      const value = choices.has(n) ? choices.get(n) : true;
      run.branches.push({ node: n, test: node.test, value, time, action: run.actions.length });
      n = value ? node.on_true : node.on_false;
      continue;
    }
    run.actions.push({ node: n, name: node.action, start: time, end: time + node.duration });
    for (const motion of node.motions) {
      const starts = [];
      let total = 0;
      for (const d of motion.durations) {
        starts.push(total);
        total += d;
      }
      run.motionsOf[motion.robot].push({
        start: time + motion.start,
        duration: total,
        starts,
        durations: motion.durations,
        waypoints: motion.waypoints,
      });
    }
    for (const event of node.events) run.events.push({ ...event, time: time + event.time });
    time += node.duration;
    n = node.next;
  }
  run.duration = time;
  return run;
}

// Robot `robot`'s configuration at time t into q: along its last motion started by t, else held
// where it ended, else its initial configuration (exec::Schedule::sample).
export function sampleRobot(run, data, robot, t, q) {
  const motions = run.motionsOf[robot];
  let last = -1;
  let lo = 0;
  let hi = motions.length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (motions[mid].start <= t) {
      last = mid;
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  if (last < 0) {
    const initial = data.robots[robot].initial;
    for (let j = 0; j < initial.length; ++j) q[j] = initial[j];
    return q;
  }
  const motion = motions[last];
  const waypoints = motion.waypoints;
  if (motion.durations.length === 0) {
    for (let j = 0; j < q.length; ++j) q[j] = waypoints[0][j];
    return q;
  }
  const local = Math.min(Math.max(t - motion.start, 0), motion.duration);
  let i = 0;
  while (i + 1 < motion.starts.length && motion.starts[i + 1] <= local) ++i;
  const duration = motion.durations[i];
  const tau = Math.min(Math.max(local - motion.starts[i], 0), duration) / duration;
  const s = tau * tau * tau * (10 + tau * (-15 + 6 * tau));
  for (let j = 0; j < q.length; ++j) {
    q[j] = waypoints[i][j] + s * (waypoints[i + 1][j] - waypoints[i][j]);
  }
  return q;
}
