// The page's hand on viser's 3D view, through the scene and camera controls viser exposes on
// window.__viserMutable (viser 1.1.1 publishes it for end-to-end tests; the browser tests check
// it is there). Right before each frame is drawn (the scene's onBeforeRender) it puts the drone
// where the pose stream says it is at that instant (static/poses.js), moves the camera after the
// drone, smoothly, when the view follows it, shortens the trail when static/quality.js asks for
// less, and lets static/answer.js place the setpoint marker. It switches the camera between the
// labs' views (GET /page/views), remembering the choice in the browser, and measures what each
// frame costs the main thread.
(() => {
  "use strict";
  const STORE_VIEW = "teleop.view", STORE_FOLLOW = "teleop.follow";
  const DISPLAY_DELAY_MS = 10;  // one pose period behind the stream: between two poses, not past them
  const POSE_STALE_MS = 1000;  // no pose for this long: leave the drone where the server drew it
  const FOLLOW_TAU_S = 0.15;  // the camera's lag behind the drone
  const FOLLOW_SLACK_M = 0.01;  // and how far the drone may wander (hovering) before the camera moves
  // Keep frames coming while the drone moves: more than 5 mm or 0.5 degrees in the last 0.1 s of
  // the pose stream. A hovering drone's jitter (a millimetre or two, back and forth) is not worth
  // a frame, nor the wait that a key pressed then would have behind it.
  const MOTION_WINDOW_MS = 100, MOVED_M = 0.005, TURNED_RAD = (0.5 * Math.PI) / 180;
  const KEEP_FRAMES = 120;
  const state = { views: [], view: null, follow: localStorage.getItem(STORE_FOLLOW) !== "fixed", ready: false,
    listeners: [], beforeFrame: [], afterFrame: [], renders: 0, frameCosts: [], trailLimit: Infinity,
    viser: null, renderer: null, vehicle: null };
  window.__teleopScene = state;
  const poses = window.__teleopPoses;
  let viser = null, V3 = null;
  let followPoint = null, lastFrame = -1, lastFollow = 0, drawStart = null;

  const ref = (name) => (typeof name === "string" && viser ? viser.nodeRefFromName[name] || null : null);
  const toThree = (p) => {  // a world point (z up) to three.js's frame: viser turns its root to y up
    const v = new V3(p[0], p[1], p[2]);
    const pose = viser.nodePoseData[""];  // the root's pose as the server set it, applied or not yet
    if (!pose) return v;
    const [w, x, y, z] = pose.wxyz;
    return v.applyQuaternion(viser.camera.quaternion.clone().set(x, y, z, w));
  };
  state.ref = ref;
  state.toThree = toThree;
  const emit = (event) => {
    for (const listener of state.listeners) {
      try { listener(event); } catch (err) { console.error(err); }
    }
  };
  const each = (hooks, ...args) => {
    for (const hook of hooks) {
      try { hook(...args); } catch (err) { console.error(err); }
    }
  };

  state.setView = (name, follow = state.follow) => {
    const view = state.views.find((v) => v.name === name) || state.views[0];
    if (!view || !viser || !viser.cameraControl) return;
    state.view = view; state.follow = follow;
    localStorage.setItem(STORE_VIEW, view.name);
    localStorage.setItem(STORE_FOLLOW, follow ? "follow" : "fixed");
    let position = view.position, target = view.look_at;
    const node = view.follow && follow ? ref(view.follow.node) : null;
    if (node) {
      target = node.position.toArray();
      position = target.map((v, i) => v + view.follow.offset[i]);
    }
    const p = toThree(position), t = toThree(target);
    viser.cameraControl.setLookAt(p.x, p.y, p.z, t.x, t.y, t.z, false);
    followPoint = null;
    emit({ type: "view", view: view.name, follow });
  };

  const followCamera = (node, now) => {
    const cc = viser.cameraControl;
    if (!cc) return;
    const goal = node.getWorldPosition(new V3());
    const dt = Math.min(Math.max((now - lastFollow) / 1000, 0), 0.2);
    lastFollow = now;
    if (!followPoint) followPoint = cc.getTarget(new V3());
    if (followPoint.distanceTo(goal) < FOLLOW_SLACK_M) return;
    followPoint.lerp(goal, 1 - Math.exp(-dt / FOLLOW_TAU_S));
    cc.moveTo(followPoint.x, followPoint.y, followPoint.z, false);
    cc.update(0);  // this frame, not the next: the camera and the drone move together
    viser.camera.updateMatrixWorld();
  };

  const limitTrail = () => {
    const trail = ref(state.vehicle && state.vehicle.trail);
    if (!trail) return;
    trail.traverse((o) => {
      if (o.geometry && o.geometry.isInstancedBufferGeometry) o.geometry.instanceCount = state.trailLimit;
    });
  };

  const beforeRender = (renderer) => {
    const now = document.timeline.currentTime;
    if (now === lastFrame) return;  // once per frame, however many passes draw it
    lastFrame = now;
    drawStart = performance.now();
    state.renderer = renderer;
    state.renders++;
    poses.sync();  // the newest poses the worker has, for this frame
    const drone = ref(state.vehicle && state.vehicle.node);
    const latest = poses.latest();
    if (drone && latest && poses.nowEpochMs() - latest.arrived < POSE_STALE_MS) {
      const pose = poses.poseAt(poses.nowEpochMs() - DISPLAY_DELAY_MS);
      drone.position.set(pose.p[0], pose.p[1], pose.p[2]);
      drone.quaternion.set(pose.q[1], pose.q[2], pose.q[3], pose.q[0]);
      drone.updateMatrixWorld(true);
      const before = poses.poseAt(poses.nowEpochMs() - DISPLAY_DELAY_MS - MOTION_WINDOW_MS);
      const moved = Math.hypot(...pose.p.map((v, i) => v - before.p[i]));
      const dot = Math.min(1, Math.abs(pose.q.reduce((d, v, i) => d + v * before.q[i], 0)));
      if (moved > MOVED_M || 2 * Math.acos(dot) > TURNED_RAD) viser.requestRender();
    }
    each(state.beforeFrame, now);
    if (drone && state.follow && state.view && state.view.follow) followCamera(drone, now);
    limitTrail();
  };

  // A task posted while drawing runs once the frame is committed (in software WebGL, after the
  // picture has been read back from the renderer): the main thread's whole cost of the frame,
  // which keys and poses wait behind. static/quality.js keeps it short.
  const frameChannel = new MessageChannel();
  frameChannel.port1.onmessage = (ev) => {
    state.frameCosts.push(performance.now() - ev.data);
    if (state.frameCosts.length > KEEP_FRAMES) state.frameCosts.shift();
  };
  const afterRender = () => {
    if (drawStart === null) return;
    frameChannel.port2.postMessage(drawStart);
    drawStart = null;
    each(state.afterFrame);
  };

  const hook = (scene) => {
    const before = scene.onBeforeRender, after = scene.onAfterRender;
    scene.onBeforeRender = function (renderer, ...rest) { before.call(this, renderer, ...rest); beforeRender(renderer); };
    scene.onAfterRender = function (...args) { after.apply(this, args); afterRender(); };
  };

  // Wait for viser's scene, camera controls and the labs' nodes, then take over the camera.
  const start = async () => {
    const views = await (await fetch("/page/views")).json();
    state.views = views.views;
    const followed = state.views.find((v) => v.follow);
    state.vehicle = followed ? followed.follow : null;
    const wanted = localStorage.getItem(STORE_VIEW);
    const first = state.views.some((v) => v.name === wanted) ? wanted : views.suggested;
    const labNodes = () => Object.keys(viser.nodeRefFromName).filter((n) => n.split("/").length > 2).length;
    const poll = () => {
      viser = window.__viserMutable || null;
      if (!viser || !viser.scene || !viser.cameraControl || !viser.camera || labNodes() === 0) {
        setTimeout(poll, 100);
        return;
      }
      state.viser = viser;
      V3 = viser.camera.position.constructor;
      hook(viser.scene);
      // viser applies its initial camera in an effect after the scene arrives: go after it.
      requestAnimationFrame(() => requestAnimationFrame(() => {
        state.setView(first);
        state.ready = true;
        emit({ type: "ready" });
      }));
    };
    poll();
  };
  start().catch((err) => console.error("teleop: no camera views", err));
})();
