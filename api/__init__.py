"""The HTTP and WebSocket API, one router per resource, gathered here."""

from fastapi import APIRouter

from . import (
    bag,
    classroom,
    introspection,
    lab_routes,
    launch_routes,
    publishers,
    rosbridge,
    services,
    topics,
    ws_keys,
    ws_topics,
)


def build_router() -> APIRouter:
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
        classroom,
        rosbridge,
    ):
        router.include_router(module.router)
    return router
