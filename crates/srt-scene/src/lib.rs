//! Scene description for srt: triangle meshes with materials, each object resting in its own
//! inertial frame; the observer and light at rest in S; TOML scene files; built-in scenes; and
//! model import from glTF 2.0, Wavefront OBJ, PLY and STL.

pub mod assets;
pub mod builtin;
pub mod choice;
pub mod corpus;
pub mod description;
pub mod edit;
pub mod import;
pub mod input_file;
pub mod limits;
pub mod mesh;
pub mod message;
pub mod mip;
pub mod placement;
pub mod projection;
pub mod resolve;
pub mod scene;
pub mod shapes;
pub mod sky;
pub mod textures;
pub mod upload;
pub mod view;

pub use builtin::{BuiltinScene, builtin, builtin_scenes};
pub use choice::{Choice, UnknownChoice};
pub use description::{
    LightDescription, LightsDescription, ObjectDescription, ObserverDescription, OverrideNames,
    Overrides, RenderDescription, Scale, SceneDescription, SceneError, SceneErrorKind, Setting,
    ShapeDescription, TextureDescription, ValueName, load_scene_file, parse_vector,
};
pub use edit::{EditError, Editor};
pub use import::{ImportError, ImportFailure, Model, load_model};
pub use mesh::{Material, Mesh, MeshError, Part, Texture};
pub use projection::{EyePoint, Projection, Stereo};
pub use resolve::{LoadedScene, ResolveError, SceneSource};
pub use scene::{
    Blink, BodyExtent, Clock, DEFAULT_CUBE_MAP_SIZE, Effects, Emission, Kinematics, Light,
    MAX_CUBE_MAP_SIZE, MAX_MOVING_LIGHTS, MovingLight, Object, Observer, Scene, Shading,
    SurfaceColour, SurfaceOptics, ViewRays,
};
pub use sky::{Sky, SkyError, Star};
pub use upload::UploadKey;
pub use view::{View, ViewError};
