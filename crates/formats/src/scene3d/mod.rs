//! The 3D view of a trace for Foxglove's 3D panel: the scene's geometry (ground, body,
//! supports), the body's pose rebuilt from the trace's channels, and the total support
//! forces as arrows — encoded as the well-known Foxglove schemas in their ROS 2 form,
//! `foxglove_msgs/msg/SceneUpdate` and `foxglove_msgs/msg/FrameTransforms` in CDR (a
//! third of the JSON bytes, compressed: docs/performance.md §2), and `foxglove.Log` in JSON.
//!
//! Conventions (Foxglove's: x right, y into the screen, z up). A planar scene moves in the
//! x–z plane; a counter-clockwise rotation θ as seen with x right and z up (the trace's
//! sign convention) is a rotation by −θ about +y. A bidirectional (3D) scene moves in x
//! and y: the centre of mass from `cm_x`/`cm_y` (else the base point's `rel_disp`/
//! `rel_disp_y`), the orientation from the rotation vector (`rotation_x`, −`rotation`,
//! `rotation_z`), the ground from `ground_disp`/`ground_disp_y`, its supports on the
//! `supports` × `support_rows` grid; the oscillator, which has no geometry, is drawn as a
//! cube on its one contact, sized from the largest displacement of the runs so that the
//! motion shows. Each run gets its own lane along y so that engines can be compared side
//! by side; the reference is drawn as a translucent ghost. Frames, per run label `L`:
//!
//! ```text
//! world ─▶ L/ground   translation (ground_disp, lane y + ground_disp_y, 0): the moving ground
//!          └▶ L/body  translation (x_cm, y_cm, z_cm0 + cm_z), rotation: origin at the centre of mass
//! ```
//!
//! The ROS 2 definitions below are written here from the field lists of Foxglove's message
//! schemas (foxglove_msgs); the 3D panel recognises the messages by schema *name*
//! (`foxglove_msgs/msg/…`, as it does `foxglove.…`) and decodes them with the definition
//! the file carries. The messages are built as JSON values with the definitions' field
//! names ([`encode`] writes them in CDR, [`decode`] reads them back); the two written at
//! every frame, the transforms and the force arrows, are also written straight in CDR
//! ([`encode_frame_transforms`], [`encode_forces`]: the same bytes without a JSON value
//! between, which cost most of the trace files' time).

mod codec;
mod forces;
mod geometry;
mod log;
mod msg;
mod pose;
mod scene;
mod transforms;
mod values;

pub use codec::{decode, encode};
pub use forces::{encode_forces, forces};
pub use geometry::Geometry;
pub use log::{log, log_schema};
pub use msg::{FRAME_TRANSFORMS, Msg, SCENE_UPDATE, Ty, definition, message_type};
pub use pose::{Pose, drawable, rotate};
pub use scene::{datum, static_scene};
pub use transforms::{
    body_transform, encode_frame_transforms, frame_transforms, ground_transform, transform,
};
pub use values::{frames, lane_color, ros_time, time_json};

#[cfg(test)]
mod tests;
