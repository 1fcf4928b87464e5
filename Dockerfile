# lienewton-server image. Build stage: Debian bookworm with the same dependency script as the README and CI
# (scripts/deps.sh build), CMake Release build. Runtime stage: bookworm-slim with only the shared libraries
# the binaries need (RUNTIME_LIBS, checked against ldd by scripts/check_runtime_libs.sh) and the font the
# renderer reads (RUNTIME_DATA), nginx in front of the server under tini (RUNTIME_FRONT,
# deploy/container/entrypoint.sh, which starts a server that crashed again), the dashboard, a non-root user.
#   docker build -t lienewton .
#   docker run --rm -p 8080:8080 lienewton
#   docker run --rm -p 8080:8080 -e LIENEWTON_METRICS_ALLOW=10.0.0.0/8 lienewton   # /metrics beyond loopback
FROM debian:bookworm AS build
WORKDIR /src
COPY scripts/deps.sh scripts/packages-build.txt scripts/packages-test.txt scripts/
RUN scripts/deps.sh build && apt-get install -y -qq --no-install-recommends ccache && rm -rf /var/lib/apt/lists/*
COPY . .
# No -march=native: the image must run on any x86-64 host, not only the build machine. No Python module: the
# image serves HTTP. ccache in a cache mount (kept by the builder between builds, never in the image): a rebuild
# after a change compiles only what the change touched.
RUN --mount=type=cache,id=lienewton-ccache,target=/root/.cache/ccache \
    cmake -S . -B /build -DCMAKE_BUILD_TYPE=Release -DLIENEWTON_NATIVE=OFF -DLIENEWTON_TESTS=OFF -DLIENEWTON_PYTHON=OFF \
      -DLIENEWTON_BENCH=OFF -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
 && CCACHE_BASEDIR=/src cmake --build /build -j"$(nproc)" --target lienewton lienewton-server

FROM debian:bookworm-slim AS runtime
# Packages of the NEEDED libraries of lienewton and lienewton-server and of OSMesa, which the renderer opens when it
# first draws, beyond the base image (libc6, libstdc++6, libgcc-s1); apt brings their own dependencies (LLVM for
# llvmpipe, OpenSSL, zlib, brotli).
ARG RUNTIME_LIBS="libcpp-httplib0.11 libosmesa6 libpng16-16 libstb0 libwebp7 libwebpmux3"
# Not visible to ldd: the TrueType font the heatmap labels are drawn with.
ARG RUNTIME_DATA="fonts-dejavu-core"
# The supported deployment in one image: nginx in front of the server, tini as PID 1 (reaps, forwards signals).
ARG RUNTIME_FRONT="nginx tini"
# policy-rc.d: installing nginx must not start it as a service during the build.
RUN printf '#!/bin/sh\nexit 101\n' >/usr/sbin/policy-rc.d && chmod 755 /usr/sbin/policy-rc.d \
 && apt-get update \
 && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends ${RUNTIME_LIBS} ${RUNTIME_DATA} \
      ${RUNTIME_FRONT} \
 && rm -rf /var/lib/apt/lists/* /usr/sbin/policy-rc.d \
 && useradd --system --uid 10001 --no-create-home --shell /usr/sbin/nologin lienewton
COPY --from=build /build/bin/lienewton /build/bin/lienewton-server /opt/lienewton/bin/
COPY web /opt/lienewton/web
COPY deploy/container/entrypoint.sh /opt/lienewton/bin/
COPY deploy/nginx/make_conf.sh deploy/nginx/lienewton.conf /opt/lienewton/nginx/
# The healthcheck reads the same variables as the server, so it probes the address nginx listens on (the
# entrypoint moves the server itself to 127.0.0.1:LIENEWTON_BACKEND_PORT behind it).
ENV LIENEWTON_HOST=0.0.0.0 \
    LIENEWTON_PORT=8080 \
    LIENEWTON_WEB_ROOT=/opt/lienewton/web \
    LP_NUM_THREADS=1
USER 10001:10001
EXPOSE 8080
HEALTHCHECK --interval=10s --timeout=3s --start-period=5s --retries=3 \
  CMD ["/opt/lienewton/bin/lienewton-server", "--healthcheck"]
# Arguments after the image name go to lienewton-server. SIGTERM drains the server and nginx, then both exit.
# A server killed by a signal is started again (the entrypoint's loop); nginx answers a JSON 502 meanwhile.
ENTRYPOINT ["/usr/bin/tini", "--", "/opt/lienewton/bin/entrypoint.sh"]
