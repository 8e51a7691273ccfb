// What a robot is doing at time t of a replay, from its detail (GET /api/runs/{id}/robots/{r},
// serve/include/smart/serve/robot_detail.hpp): `steps` carry when each action finished, when its
// Type-2 predecessors finished and when its successors' robots were ready for them.
const by = (t) => (s) => s !== null && s !== undefined && s <= t;

export function robotStatus(detail, t) {
  const steps = detail.steps || [];
  const done = by(t);
  let finished = 0;
  while (finished < steps.length && done(steps[finished].finish_s)) finished++;
  const current = finished < steps.length ? finished : -1;
  // The current action cannot start before its Type-2 predecessors finished: those not finished
  // by t are who it waits for now.
  // A 4th element true: an edge a switch of passing orders made (issue 29), drawn differently.
  const waitsNow = current < 0 ? [] : steps[current].in.filter(([, , f]) => !done(f))
    .map(([robot, action, , switched]) => ({ robot, action, switched: switched === true }));
  // Another robot ready for an action that needs one of ours not finished yet waits for us.
  const waitedByNow = [];
  for (let k = finished; k < steps.length; k++) {
    for (const [robot, action, ready, switched] of steps[k].out) {
      if (done(ready)) waitedByNow.push({ robot, action, switched: switched === true });
    }
  }
  const timed = steps.some((s) => s.finish_s !== null);
  return { finished, total: steps.length, current, type: current >= 0 ? steps[current].type : null,
           waitsNow, waitedByNow, timed };
}

// The robots in a list of edges, each once, with how many edges: "3, 17 (2)".
export function robotList(edges) {
  const count = new Map();
  for (const { robot } of edges) count.set(robot, (count.get(robot) || 0) + 1);
  return [...count].map(([r, n]) => `${r}${n > 1 ? ` (${n})` : ''}`).join(', ') || 'none';
}

// A live robot's current action and whom it waits for now, from its plan's steps (robot detail,
// steps[k].in: [robot, action, ...]) and each robot's finished count (finishedOf(robot)): the
// predecessors of its current action that are not finished yet. current -1: it is done.
export function liveStatus(steps, done, finishedOf) {
  if (done >= steps.length) return { current: -1, type: null, total: steps.length, waits: [] };
  const waits = steps[done].in.filter(([robot, action]) => finishedOf(robot) <= action).map(([robot]) => robot);
  return { current: done, type: steps[done].type, total: steps.length, waits: [...new Set(waits)] };
}
