"""Tests of the classroom: rooms, roles and polls."""
