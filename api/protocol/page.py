"""What the lab's page reads of its own: the camera views (``GET /page/views``). The views are built
by the 3D view (server/peripherals/viewer/views.py), below the API, and declared there."""

from __future__ import annotations

from server.peripherals.viewer.views import FollowJson, PageViews, ViewJson

__all__ = ["FollowJson", "PageViews", "ViewJson"]
