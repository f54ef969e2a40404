"""A version number on each room's row: several servers sharing one database write a room only over the version
they read (a write over a newer one takes that up first), and tell each other which version is current.

Revision ID: 0003
Revises: 0002
Create Date: 2026-11-29
"""

import sqlalchemy as sa
from alembic import op

revision = "0003"
down_revision = "0002"
branch_labels = None
depends_on = None


def upgrade() -> None:
    with op.batch_alter_table("rooms") as batch:
        batch.add_column(sa.Column("version", sa.Integer, nullable=False, server_default="0"))
