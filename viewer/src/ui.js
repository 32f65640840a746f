// The page's controls: play/pause, speed, the timeline, original meshes or convex pieces, the
// plan's actions (click to jump) and a choice of outcome at every sensing branch of the run.
const style = `
html, body { margin: 0; height: 100%; overflow: hidden; font: 13px system-ui, sans-serif; }
#kaboum-view { position: absolute; inset: 0 300px 52px 0; }
#kaboum-view canvas { display: block; width: 100%; height: 100%; }
#kaboum-bar { position: absolute; left: 0; right: 300px; bottom: 0; height: 52px; display: flex;
  gap: 8px; align-items: center; padding: 0 10px; box-sizing: border-box; background: #20242a;
  color: #eee; }
#kaboum-bar input[type=range] { flex: 1; }
#kaboum-bar button { min-width: 64px; }
#kaboum-time { font-variant-numeric: tabular-nums; min-width: 120px; text-align: right; }
#kaboum-side { position: absolute; top: 0; right: 0; bottom: 0; width: 300px; overflow-y: auto;
  box-sizing: border-box; padding: 8px; background: #fafafa; border-left: 1px solid #ccc; }
#kaboum-side h2 { font-size: 14px; margin: 8px 0 4px; }
#kaboum-actions { list-style: none; padding: 0; margin: 0; }
#kaboum-actions li { padding: 3px 4px; cursor: pointer; border-radius: 3px;
  font-family: monospace; }
#kaboum-actions li:hover { background: #e4e8f0; }
#kaboum-actions li.current { background: #ffd98a; }
#kaboum-actions li.sensing { cursor: default; color: #555; }
#kaboum-actions li select { margin-left: 4px; }
`;

function element(tag, attributes = {}, ...children) {
  const node = document.createElement(tag);
  Object.assign(node, attributes);
  node.append(...children);
  return node;
}

export function buildControls(title) {
  document.head.append(element('style', { textContent: style }));
  const view = element('div', { id: 'kaboum-view' });
  const play = element('button', { id: 'kaboum-play', textContent: 'Play' });
  const speed = element('select', { id: 'kaboum-speed', title: 'Playback speed' });
  for (const value of [0.25, 0.5, 1, 2, 4, 8]) {
    speed.append(element('option', { value, textContent: `${value}×`, selected: value === 1 }));
  }
  const timeline = element('input', {
    id: 'kaboum-timeline',
    type: 'range',
    min: 0,
    max: 1,
    step: 0.001,
    value: 0,
  });
  const time = element('span', { id: 'kaboum-time' });
  const pieces = element('input', { id: 'kaboum-pieces', type: 'checkbox' });
  const locations = element('input', { id: 'kaboum-locations', type: 'checkbox', checked: true });
  const bar = element(
    'div',
    { id: 'kaboum-bar' },
    play,
    speed,
    timeline,
    time,
    element('label', { title: 'The bounding convex pieces the planner used' }, pieces, 'convex'),
    element('label', {}, locations, 'locations'),
  );
  const actions = element('ol', { id: 'kaboum-actions' });
  const side = element(
    'div',
    { id: 'kaboum-side' },
    element('h2', { textContent: title || 'kaboum plan' }),
    actions,
  );
  document.body.append(view, bar, side);
  return { view, play, speed, timeline, time, pieces, locations, actions };
}

// The run's actions with each sensing branch before them, its outcome chosen by a select.
export function listRun(list, run, onSeek, onBranch) {
  list.replaceChildren();
  const items = [];
  let branch = 0;
  const addBranches = (index) => {
    while (branch < run.branches.length && run.branches[branch].action === index) {
      const { node, test, value } = run.branches[branch++];
      const select = element('select', { title: 'The outcome of this sensing branch' });
      select.dataset.node = node;
      select.append(
        element('option', { value: 'true', textContent: 'true', selected: value }),
        element('option', { value: 'false', textContent: 'false', selected: !value }),
      );
      select.addEventListener('change', () => onBranch(node, select.value === 'true'));
      list.append(element('li', { className: 'sensing' }, `sensed ${test}:`, select));
    }
  };
  run.actions.forEach((action, index) => {
    addBranches(index);
    const item = element('li', { textContent: `${action.start.toFixed(2)} s ${action.name}` });
    item.addEventListener('click', () => onSeek(action.start));
    list.append(item);
    items.push(item);
  });
  addBranches(run.actions.length);
  return items;
}
