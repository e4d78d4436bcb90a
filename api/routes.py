"""Every router of the API, gathered for the app (server/app.py)."""

from fastapi import APIRouter

from api import (
    bag,
    checkpoints,
    classroom_load,
    classroom_workspaces,
    introspection,
    lab_routes,
    launch_routes,
    publishers,
    rosbridge,
    services,
    topics,
    workspace,
    ws_keys,
    ws_output,
    ws_topics,
)
from api import classroom as classroom_routes


def build_router(*, classroom: bool = False) -> APIRouter:
    """Every route; the class server's own (api/classroom.py) are in the OpenAPI document only on a
    class server, and answer 404 elsewhere."""
    router = APIRouter()
    for module in (
        lab_routes,
        topics,
        services,
        publishers,
        launch_routes,
        introspection,
        ws_topics,
        ws_keys,
        bag,
        rosbridge,
        checkpoints,
        workspace,
        ws_output,
    ):
        router.include_router(module.router)
    router.include_router(classroom_routes.router, include_in_schema=classroom)
    router.include_router(classroom_load.router, include_in_schema=classroom)
    router.include_router(checkpoints.class_router, include_in_schema=classroom)
    router.include_router(classroom_workspaces.router, include_in_schema=classroom)
    return router
