"""Learners (no account: a browser's token and a resume code, both kept as digests) and their exercise progress.

Revision ID: 0004
Revises: 0003
Create Date: 2026-11-29
"""

import sqlalchemy as sa
from alembic import op

revision = "0004"
down_revision = "0003"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "learners",
        sa.Column("learner_id", sa.String(32), primary_key=True),
        sa.Column("resume_digest", sa.String(64), nullable=False, unique=True),
        sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
        sa.Column("used_at", sa.DateTime(timezone=True), nullable=False),
    )
    op.create_table(
        "learner_tokens",
        sa.Column("token_digest", sa.String(64), primary_key=True),
        sa.Column(
            "learner_id",
            sa.String(32),
            sa.ForeignKey("learners.learner_id", ondelete="CASCADE"),
            nullable=False,
            index=True,
        ),
    )
    op.create_table(
        "exercise_progress",
        sa.Column(
            "learner_id", sa.String(32), sa.ForeignKey("learners.learner_id", ondelete="CASCADE"), primary_key=True
        ),
        sa.Column("exercise_id", sa.String(64), primary_key=True),
        sa.Column("part_id", sa.String(32), primary_key=True),
        sa.Column("variant", sa.Integer, nullable=False),
        sa.Column("attempts", sa.Integer, nullable=False),
        sa.Column("solved", sa.Boolean, nullable=False),
        sa.Column("gave_up", sa.Boolean, nullable=False),
        sa.Column("mistakes", sa.JSON, nullable=False),
        sa.Column("updated_at", sa.DateTime(timezone=True), nullable=False),
    )
