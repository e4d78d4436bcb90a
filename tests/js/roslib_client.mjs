// npm's roslib 2.x against the lab's rosbridge, driven by node: node roslib_client.mjs WS_URL
//
// The rocket through rosbridge: subscribe to /countdown and rosout, publish {data: true} on
// /abort_takeoff and wait for the controller's "Abort Abort Abort!!!", call /rosapi/topics and
// the rocket's reset service, then wait for a new countdown from 10. Each step prints one JSON
// line; the process exits 0 when all passed, 1 on the first failure or after TIMEOUT_MS.
import { Ros, Topic, Service } from "roslib";

const TIMEOUT_MS = 40000;
const url = process.argv[2];
const report = (step, detail = {}) => console.log(JSON.stringify({ step, ...detail }));
const fail = (why) => {
  report("failed", { why: String(why) });
  process.exit(1);
};
setTimeout(() => fail(`timed out after ${TIMEOUT_MS} ms`), TIMEOUT_MS).unref();

const ros = new Ros({ url });
ros.on("error", (e) => fail(`connection error: ${e?.message ?? e}`));
const statuses = [];
ros.on("status", (s) => statuses.push(s)); // the server must send none: this client never asked

function waitFor(topic, match) {
  return new Promise((resolve) => {
    const listener = (msg) => {
      if (match(msg)) {
        topic.off("message", listener);
        resolve(msg);
      }
    };
    topic.on("message", listener);
  });
}

function call(service, request) {
  return new Promise((resolve, reject) => service.callService(request, resolve, reject));
}

await new Promise((resolve) => ros.on("connection", resolve));
report("connected");

const countdown = new Topic({ ros, name: "/countdown", messageType: "std_msgs/msg/Int64" });
const rosout = new Topic({ ros, name: "rosout", messageType: "rcl_interfaces/msg/Log" });
countdown.subscribe(() => {});
rosout.subscribe(() => {});
const counted = await waitFor(countdown, (m) => m.data > 0);
report("countdown", { data: counted.data });

const aborted = waitFor(rosout, (m) => m.name === "MainControllerNode" && m.msg === "Abort Abort Abort!!!");
const abort = new Topic({ ros, name: "abort_takeoff", messageType: "std_msgs/Bool" });
abort.publish({ data: true });
await aborted;
report("aborted");

const topics = await call(new Service({ ros, name: "rosapi/topics", serviceType: "rosapi/Topics" }), {});
if (!topics.topics.includes("/countdown")) fail(`/countdown not in ${topics.topics}`);
report("topics", { topics: topics.topics, types: topics.types });

const again = waitFor(countdown, (m) => m.data === 10);
const reset = await call(new Service({ ros, name: "/rocket/reset", serviceType: "std_srvs/srv/Trigger" }), {});
report("reset", reset);
if (reset.success !== true) fail("the reset service did not succeed");
await again;
report("countdown_again");

countdown.unsubscribe();
rosout.unsubscribe();
if (statuses.length) fail(`unexpected status ops: ${JSON.stringify(statuses)}`);
report("ok");
ros.close();
process.exit(0);
