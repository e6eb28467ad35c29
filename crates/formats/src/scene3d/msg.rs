//! The ROS 2 message types of the 3D view and their definitions (schema encoding
//! `ros2msg`).

// ---------------------------------------------------------------------------------------
// The 3D view's messages in CDR: `foxglove_msgs/msg/SceneUpdate` and
// `foxglove_msgs/msg/FrameTransforms`, the ROS 2 forms of Foxglove's well-known schemas
// (foxglove_msgs 3.x field lists, without the later `uuid`/`lineage` additions: a
// reader decodes with the definition the file carries). One table of types below gives
// the definition text, the encoder and the decoder, so the three cannot disagree.

/// A field type of a ROS 2 message definition.
#[derive(Debug)]
pub enum Ty {
    /// `float64`, 8-byte aligned.
    F64,
    /// `uint8`.
    U8,
    /// `bool` (one byte).
    Bool,
    /// `int32`, 4-byte aligned.
    I32,
    /// `uint32`, 4-byte aligned.
    U32,
    /// `string`: a `uint32` length (NUL included), the bytes, a NUL.
    Str,
    /// A nested message.
    Msg(&'static Msg),
    /// An unbounded sequence: a `uint32` count, then the elements.
    Seq(&'static Ty),
}

/// A ROS 2 message type: `package/Type` and its fields in order.
#[derive(Debug)]
pub struct Msg {
    /// `package/Type`, as dependencies are named in a definition.
    pub name: &'static str,
    /// (field name, type), in wire order.
    pub fields: &'static [(&'static str, Ty)],
}

impl Msg {
    /// The schema name Foxglove's 3D panel recognises: `package/msg/Type`.
    pub fn schema_name(&self) -> String {
        self.name.replacen('/', "/msg/", 1)
    }
}

const TIME: Msg = Msg {
    name: "builtin_interfaces/Time",
    fields: &[("sec", Ty::I32), ("nanosec", Ty::U32)],
};
const DURATION: Msg = Msg {
    name: "builtin_interfaces/Duration",
    fields: &[("sec", Ty::I32), ("nanosec", Ty::U32)],
};
const XYZ: &[(&str, Ty)] = &[("x", Ty::F64), ("y", Ty::F64), ("z", Ty::F64)];
const VECTOR3: Msg = Msg {
    name: "geometry_msgs/Vector3",
    fields: XYZ,
};
const POINT: Msg = Msg {
    name: "geometry_msgs/Point",
    fields: XYZ,
};
const QUATERNION: Msg = Msg {
    name: "geometry_msgs/Quaternion",
    fields: &[
        ("x", Ty::F64),
        ("y", Ty::F64),
        ("z", Ty::F64),
        ("w", Ty::F64),
    ],
};
const POSE: Msg = Msg {
    name: "geometry_msgs/Pose",
    fields: &[
        ("position", Ty::Msg(&POINT)),
        ("orientation", Ty::Msg(&QUATERNION)),
    ],
};
const COLOR: Msg = Msg {
    name: "foxglove_msgs/Color",
    fields: &[
        ("r", Ty::F64),
        ("g", Ty::F64),
        ("b", Ty::F64),
        ("a", Ty::F64),
    ],
};
const KEY_VALUE: Msg = Msg {
    name: "foxglove_msgs/KeyValuePair",
    fields: &[("key", Ty::Str), ("value", Ty::Str)],
};
const ARROW: Msg = Msg {
    name: "foxglove_msgs/ArrowPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("shaft_length", Ty::F64),
        ("shaft_diameter", Ty::F64),
        ("head_length", Ty::F64),
        ("head_diameter", Ty::F64),
        ("color", Ty::Msg(&COLOR)),
    ],
};
const SHAPE: &[(&str, Ty)] = &[
    ("pose", Ty::Msg(&POSE)),
    ("size", Ty::Msg(&VECTOR3)),
    ("color", Ty::Msg(&COLOR)),
];
const CUBE: Msg = Msg {
    name: "foxglove_msgs/CubePrimitive",
    fields: SHAPE,
};
const SPHERE: Msg = Msg {
    name: "foxglove_msgs/SpherePrimitive",
    fields: SHAPE,
};
const CYLINDER: Msg = Msg {
    name: "foxglove_msgs/CylinderPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("size", Ty::Msg(&VECTOR3)),
        ("bottom_scale", Ty::F64),
        ("top_scale", Ty::F64),
        ("color", Ty::Msg(&COLOR)),
    ],
};
const LINE: Msg = Msg {
    name: "foxglove_msgs/LinePrimitive",
    fields: &[
        ("type", Ty::U8),
        ("pose", Ty::Msg(&POSE)),
        ("thickness", Ty::F64),
        ("scale_invariant", Ty::Bool),
        ("points", Ty::Seq(&Ty::Msg(&POINT))),
        ("color", Ty::Msg(&COLOR)),
        ("colors", Ty::Seq(&Ty::Msg(&COLOR))),
        ("indices", Ty::Seq(&Ty::U32)),
    ],
};
const TRIANGLES: Msg = Msg {
    name: "foxglove_msgs/TriangleListPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("points", Ty::Seq(&Ty::Msg(&POINT))),
        ("color", Ty::Msg(&COLOR)),
        ("colors", Ty::Seq(&Ty::Msg(&COLOR))),
        ("indices", Ty::Seq(&Ty::U32)),
    ],
};
const TEXT: Msg = Msg {
    name: "foxglove_msgs/TextPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("billboard", Ty::Bool),
        ("font_size", Ty::F64),
        ("scale_invariant", Ty::Bool),
        ("color", Ty::Msg(&COLOR)),
        ("text", Ty::Str),
    ],
};
const MODEL: Msg = Msg {
    name: "foxglove_msgs/ModelPrimitive",
    fields: &[
        ("pose", Ty::Msg(&POSE)),
        ("scale", Ty::Msg(&VECTOR3)),
        ("color", Ty::Msg(&COLOR)),
        ("override_color", Ty::Bool),
        ("url", Ty::Str),
        ("media_type", Ty::Str),
        ("data", Ty::Seq(&Ty::U8)),
    ],
};
const ENTITY: Msg = Msg {
    name: "foxglove_msgs/SceneEntity",
    fields: &[
        ("timestamp", Ty::Msg(&TIME)),
        ("frame_id", Ty::Str),
        ("id", Ty::Str),
        ("lifetime", Ty::Msg(&DURATION)),
        ("frame_locked", Ty::Bool),
        ("metadata", Ty::Seq(&Ty::Msg(&KEY_VALUE))),
        ("arrows", Ty::Seq(&Ty::Msg(&ARROW))),
        ("cubes", Ty::Seq(&Ty::Msg(&CUBE))),
        ("spheres", Ty::Seq(&Ty::Msg(&SPHERE))),
        ("cylinders", Ty::Seq(&Ty::Msg(&CYLINDER))),
        ("lines", Ty::Seq(&Ty::Msg(&LINE))),
        ("triangles", Ty::Seq(&Ty::Msg(&TRIANGLES))),
        ("texts", Ty::Seq(&Ty::Msg(&TEXT))),
        ("models", Ty::Seq(&Ty::Msg(&MODEL))),
    ],
};
const DELETION: Msg = Msg {
    name: "foxglove_msgs/SceneEntityDeletion",
    fields: &[
        ("timestamp", Ty::Msg(&TIME)),
        ("type", Ty::U8),
        ("id", Ty::Str),
    ],
};
/// `foxglove_msgs/msg/SceneUpdate`: the static scene and the force arrows.
pub const SCENE_UPDATE: Msg = Msg {
    name: "foxglove_msgs/SceneUpdate",
    fields: &[
        ("deletions", Ty::Seq(&Ty::Msg(&DELETION))),
        ("entities", Ty::Seq(&Ty::Msg(&ENTITY))),
    ],
};
const FRAME_TRANSFORM: Msg = Msg {
    name: "foxglove_msgs/FrameTransform",
    fields: &[
        ("timestamp", Ty::Msg(&TIME)),
        ("parent_frame_id", Ty::Str),
        ("child_frame_id", Ty::Str),
        ("translation", Ty::Msg(&VECTOR3)),
        ("rotation", Ty::Msg(&QUATERNION)),
    ],
};
/// `foxglove_msgs/msg/FrameTransforms`: a run's ground and body transforms of one frame.
pub const FRAME_TRANSFORMS: Msg = Msg {
    name: "foxglove_msgs/FrameTransforms",
    fields: &[("transforms", Ty::Seq(&Ty::Msg(&FRAME_TRANSFORM)))],
};

/// The 3D view's message type of a schema name (`None`: not one of them).
pub fn message_type(schema_name: &str) -> Option<&'static Msg> {
    [&SCENE_UPDATE, &FRAME_TRANSFORMS]
        .into_iter()
        .find(|m| m.schema_name() == schema_name)
}

/// A type's name in a definition (`float64`, `foxglove_msgs/Color[]`, ...).
fn type_name(ty: &Ty) -> String {
    match ty {
        Ty::F64 => "float64".into(),
        Ty::U8 => "uint8".into(),
        Ty::Bool => "bool".into(),
        Ty::I32 => "int32".into(),
        Ty::U32 => "uint32".into(),
        Ty::Str => "string".into(),
        Ty::Msg(m) => m.name.into(),
        Ty::Seq(t) => format!("{}[]", type_name(t)),
    }
}

/// The message types `m` uses, depth first, each once.
fn dependencies(m: &'static Msg, out: &mut Vec<&'static Msg>) {
    for (_, ty) in m.fields {
        let mut ty = ty;
        while let Ty::Seq(t) = ty {
            ty = t;
        }
        if let Ty::Msg(d) = ty
            && !out.iter().any(|o| o.name == d.name)
        {
            out.push(d);
            dependencies(d, out);
        }
    }
}

/// The ROS 2 definition of `m` (schema encoding `ros2msg`): its fields, then each type
/// it uses after the 80-`=` separator and `MSG: package/Type`, as ROS 2 bundles them.
pub fn definition(m: &'static Msg) -> String {
    let fields = |m: &Msg| {
        m.fields
            .iter()
            .map(|(n, t)| format!("{} {n}\n", type_name(t)))
            .collect::<String>()
    };
    let mut deps = Vec::new();
    dependencies(m, &mut deps);
    let mut s = fields(m);
    for d in deps {
        s.push_str(&format!(
            "{}\nMSG: {}\n{}",
            "=".repeat(80),
            d.name,
            fields(d)
        ));
    }
    s
}
