"""Rotations: the one implementation of frames, attitudes and rotation sequences in Dynamics Lab.

Conventions used everywhere in the app (and by viser):

* the world (fixed) frame ``XYZ`` has +Z up; body frames are ``xyz``;
* quaternions are ``wxyz`` (scalar first), unit length;
* ``q_world_body`` and ``R_world_body`` take *body* components to *world*
  components: ``v_world = R_world_body @ v_body``; the columns of ``R_world_body``
  are the body axes in world components (many texts write the transpose,
  taking world components to body components);
* rotation sequences are body-fixed (intrinsic): ``"3-2-1"`` turns about z, then
  the new y′, then the newer x″, so ``R = R3(θ1) R2(θ2) R1(θ3)``; all twelve
  sequences are available (:data:`SEQUENCES`);
* angles in rad, rates and angular velocities in rad/s; arrays broadcast over
  leading axes (quaternions (..., 4), matrices (..., 3, 3), angle sets (..., 3)).

Modules: :mod:`.quaternions` (quaternion algebra, matrix ↔ quaternion),
:mod:`.axis_angle`, :mod:`.sequences` (the twelve sequences, angles ↔ attitude,
intermediate frames, gimbal lock), :mod:`.angular_velocity` (ω ↔ angle rates, α),
:mod:`.euler_313` (the 3-1-3 names the tops use).
"""

from app.physics.math.rotations.angular_velocity import (
    angle_rate_matrix_body,
    angle_rate_matrix_world,
    angle_rates_from_angular_velocity_body,
    angle_rates_from_angular_velocity_world,
    angular_acceleration_body,
    angular_acceleration_world,
    angular_velocity_body,
    angular_velocity_world,
)
from app.physics.math.rotations.axis_angle import (
    axis_angle_from_matrix,
    axis_angle_from_quaternion,
    matrix_from_axis_angle,
    quaternion_from_axis_angle,
)
from app.physics.math.rotations.euler_313 import (
    body_rates_from_euler_313_rates,
    euler_313_from_quaternion,
    quaternion_from_euler_313,
)
from app.physics.math.rotations.quaternions import (
    check_rotation_matrix,
    quaternion_conjugate,
    quaternion_from_matrix,
    quaternion_multiply,
    rotate_vector,
    rotation_matrix,
)
from app.physics.math.rotations.sequences import (
    GIMBAL_LOCK_TOLERANCE_RAD,
    PROPER_EULER,
    SEQUENCES,
    TAIT_BRYAN,
    RotationSequence,
    SequenceAngles,
    SequenceFrames,
    angles_from_matrix,
    angles_from_quaternion,
    elementary_quaternion,
    elementary_rotation_matrix,
    gimbal_lock_distance_rad,
    intermediate_frames,
    matrix_from_angles,
    quaternion_from_angles,
    rotation_sequence,
    wrap_angle_rad,
)

__all__ = [
    "GIMBAL_LOCK_TOLERANCE_RAD",
    "PROPER_EULER",
    "SEQUENCES",
    "TAIT_BRYAN",
    "RotationSequence",
    "SequenceAngles",
    "SequenceFrames",
    "angle_rate_matrix_body",
    "angle_rate_matrix_world",
    "angle_rates_from_angular_velocity_body",
    "angle_rates_from_angular_velocity_world",
    "angular_acceleration_body",
    "angular_acceleration_world",
    "angles_from_matrix",
    "angles_from_quaternion",
    "angular_velocity_body",
    "angular_velocity_world",
    "axis_angle_from_matrix",
    "axis_angle_from_quaternion",
    "body_rates_from_euler_313_rates",
    "check_rotation_matrix",
    "elementary_quaternion",
    "elementary_rotation_matrix",
    "euler_313_from_quaternion",
    "gimbal_lock_distance_rad",
    "intermediate_frames",
    "matrix_from_angles",
    "matrix_from_axis_angle",
    "quaternion_conjugate",
    "quaternion_from_angles",
    "quaternion_from_axis_angle",
    "quaternion_from_euler_313",
    "quaternion_from_matrix",
    "quaternion_multiply",
    "rotate_vector",
    "rotation_matrix",
    "rotation_sequence",
    "wrap_angle_rad",
]
