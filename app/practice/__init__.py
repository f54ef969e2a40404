"""Practice for a student working alone: what the practice pages keep of each learner (:mod:`.progress`)."""
