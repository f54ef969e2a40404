"""The classroom: an instructor drives one scene on a projector while the class follows it on their own devices.

One feature package, above the API and the web layer (it imports them; they never import it), holding every
classroom rule once:

- :mod:`~app.classroom.roles`: who is the instructor (the secret ``dynlab serve`` prints);
- :mod:`~app.classroom.room`: a room's state, checked whole (lesson, scene, parameters, play state, time scale,
  follow or explore, students, code format);
- :mod:`~app.classroom.registry`: every open room, by id and by code; where a room's explorers start;
- :mod:`~app.classroom.polls`: predict, then observe (answers, histogram, CSV);
- :mod:`~app.classroom.ready_questions`: the ready questions of ``lessons/polls.toml``, checked at start-up;
- :mod:`~app.classroom.qr`: the join address as a QR code;
- :mod:`~app.classroom.join_limits`: how fast students may join (per address, per room);
- :mod:`~app.classroom.schemas`: the ``/api/rooms`` request and answer models;
- :mod:`~app.classroom.routes`: the ``/api/rooms`` router;
- :mod:`~app.classroom.hub`: the room sockets (every change as it happens, the readout twice a second);
- :mod:`~app.classroom.relay`: the frame fan-out (the room's one scene, each frame sent unchanged to every follower);
- :mod:`~app.classroom.pages`: the instructor link, the join, room-viewer and projector pages;
- :mod:`~app.classroom.page_config`: the classroom's rules the page scripts need (time scales, the room socket's
  reconnect, poll and name limits), handed to them in the page's configuration.

The room's scene runs on a *stage* of the scene host (:mod:`app.scenes.host.host`); outside the host, only this
package drives stages.
"""
