// A real `smart run --mcap` (monitor + sim processes over DDS, its own domain), its recording read
// back by the ROS 2 ecosystem's own readers: @mcap/core (indexed: summary, chunk index, message
// indexes; streamed: every record from the start, chunk CRCs checked), @foxglove/rosmsg2-
// serialization for the ROS 2 view (ros2msg schemas) and @foxglove/omgidl-serialization for the
// run's own topics (omgidl schemas from idl/smart.idl). Every message is decoded; poses, tf
// frames, robot states and progress are compared with the run's states.csv and actions.csv.
// `smart run --mcap` records beside the run; the file equals `smart export mcap` of the results.
// The results files and the run's inputs ride along as attachments, so `smart serve --open
// run.mcap` replays the run from the recording alone (its states rebuilt from smart/state).
// Then `smart export mcap --ros-namespace` puts the ROS topics under a namespace, and bad input
// to `smart export` and `smart serve --open` (a cut or damaged recording, a file where a folder
// belongs) fails with exit 2 naming the file, leaving no file behind.
import { after, test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { McapIndexedReader, McapStreamReader } from '@mcap/core';
import { parse as parseRosmsg } from '@foxglove/rosmsg';
import { MessageReader as Ros2Reader } from '@foxglove/rosmsg2-serialization';
import { parseIDL } from '@foxglove/omgidl-parser';
import { MessageReader as IdlReader } from '@foxglove/omgidl-serialization';
import { decompress as zstdDecompress } from 'fzstd';

const exe = process.env.SMART_EXE;
const bench = process.env.SMART_BENCHMARKS;
const domain = process.env.SMART_DOMAIN;
const decompressHandlers = { zstd: (data) => zstdDecompress(data) };

function smart(args) {
  const r = spawnSync(exe, args, { encoding: 'utf8' });
  return { code: r.status, out: r.stdout, err: r.stderr };
}

function csvRows(file) {
  const [header, ...lines] = fs.readFileSync(file, 'utf8').split('\n').filter((l) => l.length);
  const cols = header.split(',');
  return lines.map((l) => Object.fromEntries(l.split(',').map((v, i) => [cols[i], v])));
}

// Positional readable over a file, as @mcap/core's indexed reader wants it.
function fileReadable(file) {
  const fd = fs.openSync(file, 'r');
  return {
    size: async () => BigInt(fs.fstatSync(fd).size),
    read: async (offset, length) => {
      const buf = Buffer.alloc(Number(length));
      fs.readSync(fd, buf, 0, Number(length), Number(offset));
      return new Uint8Array(buf.buffer, buf.byteOffset, buf.length);
    },
    close: () => fs.closeSync(fd),
  };
}

function decoders(schemas, channels) {
  const out = new Map();
  for (const ch of channels.values()) {
    const schema = schemas.get(ch.schemaId);
    const text = new TextDecoder().decode(schema.data);
    assert.equal(ch.messageEncoding, 'cdr', ch.topic);
    if (schema.encoding === 'ros2msg') {
      out.set(ch.id, new Ros2Reader(parseRosmsg(text, { ros2: true })));
    } else {
      assert.equal(schema.encoding, 'omgidl', ch.topic);
      out.set(ch.id, new IdlReader(schema.name, parseIDL(text)));
    }
  }
  return out;
}

async function readAll(file) {
  const readable = fileReadable(file);
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  const dec = decoders(reader.schemasById, reader.channelsById);
  const byTopic = new Map();
  let count = 0;
  for await (const m of reader.readMessages()) {
    const topic = reader.channelsById.get(m.channelId).topic;
    if (!byTopic.has(topic)) byTopic.set(topic, []);
    byTopic.get(topic).push({ logTime: m.logTime, msg: dec.get(m.channelId).readMessage(m.data) });
    ++count;
  }
  const attached = new Map();
  for await (const a of reader.readAttachments()) attached.set(a.name, Buffer.from(a.data));
  readable.close();
  return { reader, byTopic, count, attached };
}

const work = fs.mkdtempSync(path.join(os.tmpdir(), 'smart-mcap-'));
after(() => fs.rmSync(work, { recursive: true, force: true }));
const results = path.join(work, 'results');
const mcap = path.join(work, 'run.mcap');

test('a recorded run reads back with the ROS 2 ecosystem readers, equal to its results', async () => {
  const run = smart(['run', '--map', path.join(bench, 'maps/random-32-32-20.map'),
    '--scen', path.join(bench, 'scens/random-32-32-20-random-1.scen'),
    '--plan', path.join(bench, 'smart-examples/example_paths_xy.txt'), '--agents', '50',
    '--axis', 'xy', '--domain', domain, '--out', results, '--mcap', mcap, '--ros-pose-robots', '0,7',
    '--no-progress']);
  assert.equal(run.code, 0, run.err);

  // Streamed from the start: every record, each chunk's CRC checked by the reader.
  const stream = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  stream.append(new Uint8Array(fs.readFileSync(mcap)));
  const kinds = new Map();
  for (let r; (r = stream.nextRecord());) kinds.set(r.type, (kinds.get(r.type) ?? 0) + 1);
  assert.ok(stream.done(), 'the stream reader reached the closing magic');
  assert.equal(kinds.get('Header'), 1);
  assert.equal(kinds.get('Footer'), 1);
  assert.equal(kinds.get('DataEnd'), 1);

  const { reader, byTopic, count, attached } = await readAll(mcap);
  assert.equal(reader.header.profile, 'ros2');
  assert.equal(reader.statistics.messageCount, BigInt(count));
  assert.equal(kinds.get('Message'), count);
  assert.ok(reader.chunkIndexes.length > 1, 'more than one chunk');
  assert.equal(reader.chunkIndexes[0].compression, 'zstd');
  for (const ch of reader.channelsById.values()) {
    if (!ch.topic.startsWith('smart/')) assert.match(ch.metadata.get('offered_qos_profiles'), /reliability/);
  }

  const states = csvRows(path.join(results, 'states.csv'));
  const robots = 50;
  // smart/state: one RobotState per states.csv row, equal field by field.
  const recorded = byTopic.get('smart/state');
  assert.equal(recorded.length, states.length);
  recorded.forEach(({ msg }, i) => {
    const row = states[i];
    assert.equal(msg.robot_id, Number(row.robot));
    assert.equal(msg.sim_time_s, Number(row.t_s));
    assert.equal(msg.pose.x_m, Number(row.x_m));
    assert.equal(msg.pose.y_m, Number(row.y_m));
    assert.equal(msg.pose.yaw_rad, Number(row.yaw_rad));
    assert.equal(msg.queue_length, Number(row.queue));
  });

  // /smart/poses: at each state time, robot i at index i, equal to its states.csv row.
  const byTime = new Map();
  for (const row of states) {
    const t = Number(row.t_s);
    if (!byTime.has(t)) byTime.set(t, []);
    byTime.get(t).push(row);
  }
  const poses = byTopic.get('/smart/poses');
  assert.equal(poses.length, byTime.size);
  let compared = 0;
  for (const { logTime, msg } of poses) {
    assert.equal(msg.header.frame_id, 'map');
    assert.equal(msg.poses.length, robots);
    const t = msg.header.stamp.sec + msg.header.stamp.nanosec / 1e9;
    assert.ok(Math.abs(Number(logTime) / 1e9 - t) < 1e-9);
    const rows = [...byTime.entries()].find(([s]) => Math.abs(s - t) < 1e-9)[1];
    for (const row of rows) {
      const p = msg.poses[Number(row.robot)];
      assert.equal(p.position.x, Number(row.x_m));
      assert.equal(p.position.y, Number(row.y_m));
      assert.ok(Math.abs(p.orientation.z - Math.sin(Number(row.yaw_rad) / 2)) < 1e-12);
      assert.ok(Math.abs(p.orientation.w - Math.cos(Number(row.yaw_rad) / 2)) < 1e-12);
      ++compared;
    }
  }
  assert.equal(compared, states.length);
  // /tf: map -> robot_<i> for every robot, the same poses.
  const tf = byTopic.get('/tf');
  assert.equal(tf.length, poses.length);
  tf.forEach(({ msg }, k) => {
    assert.deepEqual(msg.transforms.map((x) => x.child_frame_id),
      Array.from({ length: robots }, (_, i) => `robot_${i}`));
    assert.ok(msg.transforms.every((x) => x.header.frame_id === 'map'));
    assert.equal(msg.transforms[3].transform.translation.x, poses[k].msg.poses[3].position.x);
  });
  // The chosen robots' PoseStamped equal their PoseArray entries.
  for (const r of [0, 7]) {
    const mine = byTopic.get(`/robot_${r}/pose`);
    assert.equal(mine.length, poses.length);
    mine.forEach(({ msg }, k) => assert.deepEqual(msg.pose, poses[k].msg.poses[r]));
  }
  // /smart/markers at most once a second of sim time, with a PoseArray, as the live plan view
  // draws it: the old waits cleared, each robot where the PoseArray has it, its goal; at the end
  // every robot done (grey). A marker goes with the first PoseArray a second or more after the
  // last marker, and with the last PoseArray. (Not one per second of the run: states lost on a
  // loaded machine delay a marker, and the next is a second after it.)
  const markers = byTopic.get('/smart/markers');
  const posesAt = new Map(poses.map((p) => [p.logTime, p.msg]));
  const expected = [];
  poses.forEach(({ logTime }, k) => {
    const due = expected.length === 0 || logTime - expected[expected.length - 1] >= 1000000000n;
    if (due || k + 1 === poses.length) expected.push(logTime);
  });
  assert.deepEqual(markers.map((m) => m.logTime), expected);
  assert.ok(markers.length >= 10, 'a run of minutes has a marker array every second or so');
  for (const { logTime, msg } of markers) {
    assert.equal(msg.markers[0].action, 3);  // DELETEALL
    const robotsNs = msg.markers.filter((m) => m.ns === 'robots');
    assert.equal(robotsNs.length, robots);
    assert.equal(msg.markers.filter((m) => m.ns === 'goals').length, robots);
    for (const m of robotsNs) assert.equal(m.pose.position.x, posesAt.get(logTime).poses[m.id].position.x);
  }
  const waits = markers.reduce((n, { msg }) => n + msg.markers.filter((m) => m.ns === 'waits' && m.action === 0).length, 0);
  assert.ok(waits > 0, 'some robot waited for another at a shared cell');
  const last = markers[markers.length - 1].msg.markers.filter((m) => m.ns === 'robots');
  assert.ok(last.every((m) => Math.abs(m.color.r - 0.6) < 1e-6 && Math.abs(m.color.g - 0.6) < 1e-6));
  // The map and every robot's plan, once at t = 0.
  const [map] = byTopic.get('/map');
  assert.equal(map.msg.info.width, 32);
  assert.equal(map.msg.info.height, 32);
  assert.equal(map.msg.data.length, 32 * 32);
  assert.ok(map.msg.data.some((c) => c === 100) && map.msg.data.some((c) => c === 0));
  for (let r = 0; r < robots; ++r) assert.ok(byTopic.get(`/robot_${r}/plan`)[0].msg.poses.length > 1);
  // smart/progress: one per finished action (actions.csv), in time order.
  const finished = csvRows(path.join(results, 'actions.csv')).filter((a) => a.finish_time_s !== '');
  const progress = byTopic.get('smart/progress');
  assert.equal(progress.length, finished.length);
  for (let k = 1; k < progress.length; ++k) assert.ok(progress[k].logTime >= progress[k - 1].logTime);

  // Attachments: the results files but states.csv, and the run's inputs, byte for byte.
  assert.equal(reader.statistics.attachmentCount, attached.size);
  for (const f of ['summary.json', 'stats.csv', 'robots.csv', 'actions.csv']) {
    assert.ok(attached.get(f).equals(fs.readFileSync(path.join(results, f))), f);
  }
  assert.ok(!attached.has('states.csv'));
  const plan = attached.get('input/plan/example_paths_xy.txt');
  assert.ok(plan.equals(fs.readFileSync(path.join(bench, 'smart-examples/example_paths_xy.txt'))));
  assert.ok(attached.has('input/map/random-32-32-20.map') && attached.has('input/scen/random-32-32-20-random-1.scen'));

  // Recorded while the run went, it is the file `smart export mcap` makes of its results.
  const again = path.join(work, 'again.mcap');
  const e = smart(['export', 'mcap', results, '-o', again, '--ros-pose-robots', '0,7']);
  assert.equal(e.code, 0, e.err);
  assert.ok(fs.readFileSync(again).equals(fs.readFileSync(mcap)), 'the live recording equals the export');
});

// `smart serve --open FILE`; resolves with its URL and the runs it opened once it listens.
function serveOpen(file, data) {
  const server = spawn(exe, ['serve', '--port', '0', '--data', data, '--open', file, '--domain', domain]);
  let err = '';
  server.stderr.on('data', (d) => { err += d; });
  return new Promise((resolve, reject) => {
    let text = '';
    server.stdout.on('data', (d) => {
      text += d;
      const m = text.match(/^(\{.*"listening".*\})$/m);
      if (m) resolve({ server, info: JSON.parse(m[1]) });
    });
    server.on('exit', (code) => reject(new Error(`smart serve exited (${code}): ${err}`)));
  });
}

test('smart serve --open replays a recording from the file alone', async () => {
  // Elsewhere: only the recording, no results folder beside it.
  const away = path.join(work, 'away');
  fs.mkdirSync(away);
  const copy = path.join(away, 'run.mcap');
  fs.copyFileSync(mcap, copy);
  const { server, info } = await serveOpen(copy, path.join(away, 'data'));
  try {
    const [id] = info.opened;
    const base = `${info.listening}/api/runs/${id}`;
    const states = await (await fetch(`${base}/results/states.csv`)).text();
    assert.equal(states, fs.readFileSync(path.join(results, 'states.csv'), 'utf8'));
    const actions = await (await fetch(`${base}/results/actions.csv`)).text();
    assert.equal(actions, fs.readFileSync(path.join(results, 'actions.csv'), 'utf8'));
    const run = await (await fetch(base)).json();
    assert.equal(run.state, 'done');
    assert.equal(run.robots, 50);
    assert.equal(run.map, 'random-32-32-20.map');
    // The robot panel needs the plan: it came from the attachments.
    const robot = await (await fetch(`${base}/robots/3`)).json();
    assert.ok(robot.path.length > 1 && robot.actions > 0, JSON.stringify(robot).slice(0, 200));
  } finally {
    server.kill('SIGTERM');
  }
});

test('a cut or damaged recording given to smart serve --open or smart export is named, exit 2', () => {
  const bytes = fs.readFileSync(mcap);
  const cut = path.join(work, 'cut.mcap');
  fs.writeFileSync(cut, bytes.subarray(0, Math.floor(bytes.length / 2)));
  const damaged = path.join(work, 'damaged.mcap');
  const flipped = Buffer.from(bytes);
  flipped[Math.floor(bytes.length / 3)] ^= 0x40;
  fs.writeFileSync(damaged, flipped);
  const open = (file) => spawnSync(exe, ['serve', '--port', '0', '--data', path.join(work, 'bad-data'),
    '--open', file, '--domain', domain], { encoding: 'utf8', timeout: 120000 });
  const c = open(cut);
  assert.equal(c.status, 2, c.stderr);
  assert.match(c.stderr, new RegExp(`${cut}: the file ends at byte \\d+ inside .* cut short`));
  const d = open(damaged);
  assert.equal(d.status, 2, d.stderr);
  assert.match(d.stderr, new RegExp(`${damaged}: byte \\d+: .*(CRC-32|zstd)`));
  const csv = open(path.join(results, 'states.csv'));
  assert.equal(csv.status, 2, csv.stderr);
  assert.match(csv.stderr, /does not start with the MCAP magic/);
  const e = smart(['export', 'mcap', mcap]);
  assert.equal(e.code, 2, e.err);
  assert.match(e.err, /run\.mcap: a file, not a results folder/);
});

test('smart export mcap puts the ROS 2 view under a namespace', async () => {
  const out = path.join(work, 'ns.mcap');
  const r = smart(['export', 'mcap', results, '-o', out, '--ros-namespace', '/run_b']);
  assert.equal(r.code, 0, r.err);
  const { byTopic } = await readAll(out);
  for (const topic of ['/run_b/map', '/run_b/tf', '/run_b/smart/poses', '/run_b/smart/markers', '/run_b/robot_3/plan', 'smart/state']) {
    assert.ok(byTopic.has(topic), `${topic} in ${[...byTopic.keys()].slice(0, 8)}`);
  }
  assert.ok(!byTopic.has('/tf'));
});

test('smart export mcap writes RESULTS_DIR/run.mcap when no file is named', async () => {
  const copy = path.join(work, 'default-name');
  fs.cpSync(results, copy, { recursive: true });
  const r = smart(['export', 'mcap', copy]);
  assert.equal(r.code, 0, r.err);
  const { byTopic } = await readAll(path.join(copy, 'run.mcap'));
  assert.ok(byTopic.has('/tf') && byTopic.has('smart/state'), [...byTopic.keys()].slice(0, 8).join(' '));
});

test('bad input to smart export names the file and leaves no file', () => {
  const bad = path.join(work, 'bad');
  fs.mkdirSync(bad);
  for (const f of ['summary.json', 'actions.csv']) fs.copyFileSync(path.join(results, f), path.join(bad, f));
  const lines = fs.readFileSync(path.join(results, 'states.csv'), 'utf8').split('\n');
  lines[5] = lines[5].slice(0, 7);  // a torn row
  fs.writeFileSync(path.join(bad, 'states.csv'), lines.join('\n'));
  const out = path.join(work, 'bad.mcap');
  const r = smart(['export', 'mcap', bad, '-o', out]);
  assert.equal(r.code, 2, r.err);
  assert.match(r.err, /states\.csv:6: not a state row/);
  assert.ok(!fs.existsSync(out) && !fs.existsSync(`${out}.part`));
  const none = smart(['export', 'mcap', work, '-o', out]);
  assert.equal(none.code, 2);
  assert.match(none.err, /summary\.json: not found/);
});
