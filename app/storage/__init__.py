"""What a class makes and must not lose, kept in one SQL database.

SQLite in the data directory by default (``--data-dir`` / ``DYNLAB_DATA_DIR``), or any database SQLAlchemy speaks
by URL (``DYNLAB_DATABASE_URL``, e.g. PostgreSQL). :mod:`.tables` is the schema, :mod:`.database` opens the database
and brings its schema up to date (Alembic migrations in :mod:`.migrations`, forward only, at start-up).
"""

from app.storage.database import Database, default_data_dir, open_database

__all__ = ["Database", "default_data_dir", "open_database"]
