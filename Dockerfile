# Dynamics Lab server: the same install steps as the README (uv from PyPI, then `uv run`).
FROM python:3.11-slim
ENV PYTHONUNBUFFERED=1 UV_COMPILE_BYTECODE=1 UV_LINK_MODE=copy
WORKDIR /srv/dynlab
RUN python3 -m pip install --no-cache-dir uv
COPY pyproject.toml uv.lock README.md ./
RUN python3 -m uv sync --frozen --no-dev --group postgres --no-install-project
COPY app ./app
COPY static ./static
COPY lessons ./lessons
# The `postgres` group is PostgreSQL's driver, for DYNLAB_DATABASE_URL (deploy/compose.yaml).
RUN python3 -m uv sync --frozen --no-dev --group postgres
# Derive and compile the chapter 7-9 scenes' equations into the image's caches (sympy and numba), so the
# first class after a start does not wait for them.
RUN python3 -m uv run --frozen --no-dev dynlab warm
# The class's data (rooms, answers, the instructor's secret): keep it on a volume, `docker run -v dynlab-data:/data …`.
ENV DYNLAB_DATA_DIR=/data
VOLUME /data
EXPOSE 8000
CMD ["python3", "-m", "uv", "run", "--frozen", "--no-dev", "--group", "postgres", "dynlab", "serve", "--host", "0.0.0.0", "--port", "8000"]
