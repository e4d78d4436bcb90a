"""Every router of the API, gathered for the app (server/app.py)."""

from fastapi import APIRouter

from api.routes import (
    bag,
    checkpoints,
    classroom_load,
    classroom_workspaces,
    introspection,
    lab,
    launches,
    publishers,
    services,
    topics,
    workspace,
)
from api.routes import classroom as classroom_routes
from api.websockets import echo, keys, output, rosbridge


def build_router(*, classroom: bool = False) -> APIRouter:
    """Every route; the class server's own (api/routes/classroom.py) are in the OpenAPI document only on a
    class server, and answer 404 elsewhere."""
    router = APIRouter()
    for module in (
        lab,
        topics,
        services,
        publishers,
        launches,
        introspection,
        echo,
        keys,
        bag,
        rosbridge,
        checkpoints,
        workspace,
        output,
    ):
        router.include_router(module.router)
    router.include_router(classroom_routes.router, include_in_schema=classroom)
    router.include_router(classroom_load.router, include_in_schema=classroom)
    router.include_router(checkpoints.class_router, include_in_schema=classroom)
    router.include_router(classroom_workspaces.router, include_in_schema=classroom)
    return router
