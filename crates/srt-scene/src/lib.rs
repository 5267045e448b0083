//! Scene description for srt: triangle meshes with materials, each object resting in its own
//! inertial frame; the observer and light at rest in S; TOML scene files; built-in scenes; and
//! model import from glTF 2.0, Wavefront OBJ, PLY and STL.

pub mod mesh;

pub use mesh::{Material, Mesh, MeshError, Part, Texture};
