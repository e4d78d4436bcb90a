// The lab page's script, injected into viser's own page before its scripts (server: the page's
// routes). Key capture first: it must see keys before viser does. Then the pose stream, the
// setpoint prediction, the scene driver (views, follow), the drawn answer to a key, the drawing
// quality, the HUD, the tools link, the lab's guide (web/src/guide: checkpoints, answers, the
// view's picture for checkpoint 2), the layout inside the scene's pane, the code view (its editor
// loads as a bundle of its own when first opened), the workbench that lays these out as panes,
// and the view that follows what the student's code flies.
//
// The modules share their state through imports. window.__teleop exposes the same objects to
// the browser tests and benches (bench/teleop_latency.py), and to a curious student's console.
import { capture, startCapture } from "../guide/capture";
import { guide, startGuide } from "../guide/panel";
import { progress, startProgress } from "../guide/progress";
import { answer, startAnswer } from "./answer";
import { autoview, startAutoview } from "./autoview";
import { codeview, startCodeView } from "./codeview";
import { hud, startHud } from "./hud";
import { keys, startKeys } from "./keys";
import { layout, startLayout } from "./layout";
import { startNav } from "./nav";
import { poses, startPoses } from "./poses";
import { predict, startPredict } from "./predict";
import { quality, startQuality } from "./quality";
import { scene, startScene } from "./scene";
import { startWorkbench, workbench } from "./workbench";

const teleop = {
  keys, poses, predict, scene, answer, quality, hud, layout, codeview, workbench, autoview,
  guide: { panel: guide, progress, capture },
};
declare global {
  interface Window { __teleop?: typeof teleop }
}

startKeys();
startPoses();
startPredict();
startScene();
startAnswer();
startQuality();
startHud();
startNav();
startGuide();
startProgress();
startCapture();
startLayout();
startCodeView();
startWorkbench();
startAutoview();
window.__teleop = teleop;
