"""Alembic's environment: migrations run on the connection :func:`app.storage.database.migrate` hands over."""

from alembic import context

from app.storage.tables import metadata

connection = context.config.attributes["connection"]
# SQLite alters a table by copying it: Alembic's batch mode does that.
context.configure(connection=connection, target_metadata=metadata, render_as_batch=connection.dialect.name == "sqlite")
with context.begin_transaction():
    context.run_migrations()
