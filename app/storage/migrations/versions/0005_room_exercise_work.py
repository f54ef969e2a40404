"""A room's record of its students' work on the exercises it assigned (issue 27, point 7).

Revision ID: 0005
Revises: 0004
Create Date: 2026-11-29
"""

import sqlalchemy as sa
from alembic import op

revision = "0005"
down_revision = "0004"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "room_exercise_work",
        sa.Column("room_id", sa.String(32), sa.ForeignKey("rooms.room_id", ondelete="CASCADE"), primary_key=True),
        sa.Column("student_id", sa.String(16), primary_key=True),
        sa.Column("exercise_id", sa.String(64), primary_key=True),
        sa.Column("part_id", sa.String(32), primary_key=True),
        sa.Column("variant", sa.Integer, nullable=False),
        sa.Column("attempts", sa.Integer, nullable=False),
        sa.Column("solved", sa.Boolean, nullable=False),
        sa.Column("gave_up", sa.Boolean, nullable=False),
        sa.Column("mistakes", sa.JSON, nullable=False),
        sa.Column("updated_at", sa.DateTime(timezone=True), nullable=False),
    )
