"""Pure numerics: no viser, no FastAPI. Every module here is testable on its own."""
