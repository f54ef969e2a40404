# Dynamics Lab server: the same install steps as the README (uv from PyPI, then `uv run`).
FROM python:3.11-slim
ENV PYTHONUNBUFFERED=1 UV_COMPILE_BYTECODE=1 UV_LINK_MODE=copy
WORKDIR /srv/dynlab
RUN python3 -m pip install --no-cache-dir uv
COPY pyproject.toml uv.lock README.md ./
RUN python3 -m uv sync --frozen --no-dev --no-install-project
COPY app ./app
COPY static ./static
COPY lessons ./lessons
RUN python3 -m uv sync --frozen --no-dev
EXPOSE 8000
CMD ["python3", "-m", "uv", "run", "--frozen", "--no-dev", "dynlab", "serve", "--host", "0.0.0.0", "--port", "8000"]
