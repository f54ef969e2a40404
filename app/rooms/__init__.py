"""The classroom: rooms, roles and polls."""
