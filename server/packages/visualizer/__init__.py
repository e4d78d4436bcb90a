"""The lab's visualizer package: the quadrotor's 3D view, drawn in the browser by viser."""
