"""HTML pages and the viewer websocket relay."""
