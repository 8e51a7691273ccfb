// `smart bridge` (the Foxglove WebSocket protocol) seen by @foxglove/ws-protocol's own client over
// the `ws` package: a real `smart run` (monitor + sim over DDS, its own domain) is watched live;
// the client subscribes to the advertised channels, decodes PoseArrays with the advertised ros2msg
// schema (@foxglove/rosmsg2-serialization) and finds them equal to what the run wrote to
// states.csv; a client that joins after the run still gets the latched map; hostile clients get
// status errors or are closed, and the bridge keeps serving.
import { after, test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import WebSocket from 'ws';
import wsProtocol from '@foxglove/ws-protocol';
import { parse as parseRosmsg } from '@foxglove/rosmsg';
import { MessageReader } from '@foxglove/rosmsg2-serialization';

const { FoxgloveClient } = wsProtocol;
const exe = process.env.SMART_EXE;
const bench = process.env.SMART_BENCHMARKS;
const domain = process.env.SMART_DOMAIN;
const work = fs.mkdtempSync(path.join(os.tmpdir(), 'smart-bridge-'));
after(() => fs.rmSync(work, { recursive: true, force: true }));

function startBridge() {
  const bridge = spawn(exe, ['bridge', '--foxglove-port', '0', '--domain', domain,
    '--ros-pose-robots', '7']);
  bridge.stderr.on('data', () => {});
  return new Promise((resolve, reject) => {
    let text = '';
    bridge.stdout.on('data', (d) => {
      text += d;
      const m = text.match(/"listening":"(ws:\/\/[^"]+)"/);
      if (m) resolve({ bridge, url: m[1] });
    });
    bridge.on('exit', (code) => reject(new Error(`smart bridge exited (${code}): ${text}`)));
  });
}

// A Foxglove client that subscribes to `topics` once they are advertised and decodes what comes.
function connect(url, topics) {
  const client = new FoxgloveClient({
    ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]),
  });
  const got = { byTopic: new Map(), times: [], subscribed: null };
  const subs = new Map();
  got.subscribed = new Promise((resolve) => {
    client.on('advertise', (channels) => {
      for (const ch of channels) {
        if (!topics.includes(ch.topic)) continue;
        assert.equal(ch.encoding, 'cdr');
        assert.equal(ch.schemaEncoding, 'ros2msg');
        const reader = new MessageReader(parseRosmsg(ch.schema, { ros2: true }));
        subs.set(client.subscribe(ch.id), { topic: ch.topic, reader });
        got.byTopic.set(ch.topic, []);
      }
      resolve();
    });
  });
  client.on('message', ({ subscriptionId, timestamp, data }) => {
    const { topic, reader } = subs.get(subscriptionId);
    got.byTopic.get(topic).push({ timestamp, msg: reader.readMessage(data) });
  });
  client.on('time', ({ timestamp }) => got.times.push(timestamp));
  return { client, got };
}

function until(check, what) {
  return new Promise((resolve, reject) => {
    const guard = setTimeout(() => reject(new Error(`never happened: ${what}`)), 120000);
    const poll = setInterval(() => {
      if (check()) {
        clearInterval(poll);
        clearTimeout(guard);
        resolve();
      }
    }, 20);
  });
}

test('Foxglove clients watch a running fleet through smart bridge', async () => {
  const { bridge, url } = await startBridge();
  try {
    const live = connect(url, ['/smart/poses', '/tf', '/map', '/smart/markers', '/robot_3/plan',
      '/robot_7/pose']);
    await live.got.subscribed;
    const results = path.join(work, 'results');
    // The run in its own process, while this one reads the bridge (paced at 40x real time so the
    // fleet is seen moving for a few seconds).
    const run = spawn(exe, ['run', '--map', path.join(bench, 'maps/random-32-32-20.map'),
      '--scen', path.join(bench, 'scens/random-32-32-20-random-1.scen'),
      '--plan', path.join(bench, 'smart-examples/example_paths_xy.txt'), '--axis', 'xy',
      '--agents', '50', '--domain', domain, '--out', results, '--no-progress',
      '--ros-plan-hz', '20', '--ros-pose-robots', '7', '--real-time-factor', '40']);
    let runErr = '';
    run.stderr.on('data', (d) => { runErr += d; });
    run.stdout.on('data', () => {});
    const code = await new Promise((resolve) => run.on('exit', resolve));
    assert.equal(code, 0, runErr);
    const seen = (topic) => (live.got.byTopic.get(topic) ?? []).length > 0;
    await until(() => ['/smart/poses', '/map', '/smart/markers', '/robot_3/plan', '/robot_7/pose']
      .every(seen), 'a PoseArray, the map, markers, a plan (advertised once the fleet is known) '
      + 'and a chosen robot\'s pose');
    // Robot 3's plan: the monitor's path, from its start to its goal (the scen's cells).
    const [plan3] = live.got.byTopic.get('/robot_3/plan');
    assert.ok(plan3.msg.poses.length > 1);
    assert.equal(plan3.msg.header.frame_id, 'map');
    const [{ msg: markers }] = live.got.byTopic.get('/smart/markers');
    assert.equal(markers.markers.filter((m) => m.ns === 'robots').length, 50);
    for (const { msg } of live.got.byTopic.get('/robot_7/pose')) assert.equal(msg.header.frame_id, 'map');

    // Every PoseArray received is the fleet as the run recorded it at that sim time. States are
    // best effort (config/qos, "state": latest only), so on a loaded machine the monitor may miss
    // one tick's states (one datagram, the whole fleet's) that the bridge got: such a PoseArray
    // must still be at a state time of the run (every 0.5 s up to its end) and states.csv must
    // then hold none of that tick (a lost sample, never a wrong or partial one).
    const rows = fs.readFileSync(path.join(results, 'states.csv'), 'utf8').trim().split('\n').slice(1)
      .map((l) => l.split(','));
    const at = new Map(rows.map((r) => [`${Number(r[0])}/${r[1]}`, r]));
    const end = Math.max(...rows.map((r) => Number(r[0])));
    let compared = 0;
    let missed = 0;
    for (const { timestamp, msg } of live.got.byTopic.get('/smart/poses')) {
      assert.equal(msg.header.frame_id, 'map');
      assert.equal(msg.poses.length, 50);
      const t = msg.header.stamp.sec + msg.header.stamp.nanosec / 1e9;
      assert.equal(timestamp, BigInt(msg.header.stamp.sec) * 1000000000n + BigInt(msg.header.stamp.nanosec));
      const held = msg.poses.filter((p, i) => at.has(`${t}/${i}`)).length;
      if (held === 0) {
        assert.ok(Number.isInteger(t * 2) && t > 0 && t <= end, `PoseArray at ${t} s, not a state time`);
        ++missed;
        continue;
      }
      msg.poses.forEach((p, i) => {
        const row = at.get(`${t}/${i}`);
        assert.ok(row, `robot ${i} at ${t} s in states.csv (${held} of 50 robots are)`);
        // states.csv holds 10 significant digits (results_format.hpp); the wire, the double.
        assert.ok(Math.abs(p.position.x - Number(row[2])) <= 1e-9 * Math.max(1, Math.abs(p.position.x)));
        assert.ok(Math.abs(p.position.y - Number(row[3])) <= 1e-9 * Math.max(1, Math.abs(p.position.y)));
        ++compared;
      });
    }
    assert.equal(compared + 50 * missed, 50 * live.got.byTopic.get('/smart/poses').length);
    assert.ok(compared > 0, 'PoseArrays compared with states.csv');
    const tf = live.got.byTopic.get('/tf');
    assert.ok(tf.length > 0);
    assert.equal(tf[0].msg.transforms[49].child_frame_id, 'robot_49');
    assert.ok(live.got.times.length > 0, 'time messages (the run\'s sim time)');
    const [map] = live.got.byTopic.get('/map');
    assert.equal(map.msg.info.width, 32);
    assert.equal(map.msg.data.length, 32 * 32);

    // A client that joins after the run still gets the map (latched, like transient local).
    const late = connect(url, ['/map']);
    await late.got.subscribed;
    await until(() => late.got.byTopic.get('/map').length === 1, 'the latched map');
    late.client.close();
    live.client.close();

    // Hostile clients: answered with status errors, or closed; the bridge lives on.
    const raw = new WebSocket(url, ['foxglove.websocket.v1']);
    const statuses = [];
    raw.on('message', (d, binary) => {
      if (!binary) {
        const m = JSON.parse(String(d));
        if (m.op === 'status') statuses.push(m);
      }
    });
    await new Promise((resolve) => raw.on('open', resolve));
    raw.send('not json {');
    raw.send(JSON.stringify({ op: 'subscribe', subscriptions: [{ id: 1, channelId: 999 }] }));
    raw.send(Buffer.from([1, 2, 3]));
    await until(() => statuses.length === 3, 'three status replies');
    assert.match(statuses[0].message, /not a foxglove\.websocket\.v1 message/);
    assert.match(statuses[1].message, /no channel 999/);
    assert.match(statuses[2].message, /read-only/);
    const closed = new Promise((resolve) => raw.on('close', resolve));
    raw.send('x'.repeat(100000));
    await closed;
    const plain = await fetch(url.replace('ws:', 'http:'));
    assert.equal(plain.status, 400);
    assert.match(await plain.text(), /Foxglove WebSocket bridge/);
    assert.equal(bridge.exitCode, null, 'the bridge still runs');
  } finally {
    bridge.kill('SIGTERM');
  }
});
