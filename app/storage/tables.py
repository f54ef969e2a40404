"""The database's schema (SQLAlchemy Core): one table per thing a class keeps.

Secrets a person holds (a student's token, a device's id) are kept only as SHA-256 hashes; the instructor's secret
is kept as itself, since the server prints the instructor link from it. Times are UTC.
"""

from __future__ import annotations

import sqlalchemy as sa

metadata = sa.MetaData()

#: Values the server keeps for itself, by name (``instructor_secret``).
server_values = sa.Table(
    "server_values",
    metadata,
    sa.Column("name", sa.String(64), primary_key=True),
    sa.Column("value", sa.Text, nullable=False),
    sa.Column("updated_at", sa.DateTime(timezone=True), nullable=False),
)

#: One row per room: its code, when it was last used, its record (app.classroom.room.Room.record: the shared scene's
#: lesson, scene, parameters and play state, its students by token hash, its polls without their answers) and the
#: record's version (one more with each write; a server writes only over the version it read).
rooms = sa.Table(
    "rooms",
    metadata,
    sa.Column("room_id", sa.String(32), primary_key=True),
    sa.Column("code", sa.String(16), nullable=False, unique=True),
    sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
    sa.Column("used_at", sa.DateTime(timezone=True), nullable=False),
    sa.Column("record", sa.JSON, nullable=False),
    sa.Column("version", sa.Integer, nullable=False, server_default="0"),
)

#: One row per student's answer to a poll (replaced while the poll is open); deleted with the room or the student.
answers = sa.Table(
    "answers",
    metadata,
    sa.Column("room_id", sa.String(32), sa.ForeignKey("rooms.room_id", ondelete="CASCADE"), primary_key=True),
    sa.Column("poll_id", sa.String(16), primary_key=True),
    sa.Column("student_id", sa.String(16), primary_key=True),
    sa.Column("number", sa.Integer, nullable=False),
    sa.Column("name", sa.String(64), nullable=False),
    sa.Column("choice", sa.Integer, nullable=True),
    sa.Column("value", sa.Float, nullable=True),
    sa.Column("answered_at", sa.DateTime(timezone=True), nullable=False),
)

#: One row per page session (a lesson page's own scene): its scene, its parameters and the digest of the key that
#: claimed it (None: unclaimed); forgotten when the session is evicted. No address is kept.
sessions = sa.Table(
    "sessions",
    metadata,
    sa.Column("session_id", sa.String(128), primary_key=True),
    sa.Column("scene_id", sa.String(64), nullable=False),
    sa.Column("key_digest", sa.String(64), nullable=True),
    sa.Column("params", sa.JSON, nullable=False),
    sa.Column("used_at", sa.DateTime(timezone=True), nullable=False),
)

#: One row per learner (issue 27's practice: no account). Their browsers hold secret tokens (kept in
#: ``learner_tokens`` as SHA-256 digests); a short resume code, kept as its digest, carries them to another device.
learners = sa.Table(
    "learners",
    metadata,
    sa.Column("learner_id", sa.String(32), primary_key=True),
    sa.Column("resume_digest", sa.String(64), nullable=False, unique=True),
    sa.Column("created_at", sa.DateTime(timezone=True), nullable=False),
    sa.Column("used_at", sa.DateTime(timezone=True), nullable=False),
)

#: One row per browser a learner uses: the digest of its token.
learner_tokens = sa.Table(
    "learner_tokens",
    metadata,
    sa.Column("token_digest", sa.String(64), primary_key=True),
    sa.Column(
        "learner_id",
        sa.String(32),
        sa.ForeignKey("learners.learner_id", ondelete="CASCADE"),
        nullable=False,
        index=True,
    ),
)

#: One row per learner, exercise and part: the variant they work on, attempts, solved or given up, and the ids of the
#: named mistakes their wrong answers matched (in the order made).
exercise_progress = sa.Table(
    "exercise_progress",
    metadata,
    sa.Column("learner_id", sa.String(32), sa.ForeignKey("learners.learner_id", ondelete="CASCADE"), primary_key=True),
    sa.Column("exercise_id", sa.String(64), primary_key=True),
    sa.Column("part_id", sa.String(32), primary_key=True),
    sa.Column("variant", sa.Integer, nullable=False),
    sa.Column("attempts", sa.Integer, nullable=False),
    sa.Column("solved", sa.Boolean, nullable=False),
    sa.Column("gave_up", sa.Boolean, nullable=False),
    sa.Column("mistakes", sa.JSON, nullable=False),
    sa.Column("updated_at", sa.DateTime(timezone=True), nullable=False),
)

#: One row per room, student and part of an exercise the room assigned (issue 27, point 7): the class's record of that
#: student's work, which the instructor's results read — kept apart from the learner's own progress, which the learner
#: may forget. Deleted with the room, or with the student when the instructor removes them.
room_exercise_work = sa.Table(
    "room_exercise_work",
    metadata,
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
