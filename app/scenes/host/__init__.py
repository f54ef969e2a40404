"""The viser life cycle: one loopback viser server, sessions, the frame loop (:mod:`.host`)."""
