//! Bind groups and the pipelines (proxy compute, LRT visibility, ray-tracer visibility, LRT
//! part depth, LRT shading, polygon), the object passes' in every [`ObjectVariant`] made on
//! first use.
//!
//! Every binding is described once, as data ([`Slot`], [`BindGroupSpec`]): the bind group
//! layouts, the bind groups the renderer creates and the `set_bind_group` calls all read it, and
//! `tests/reflect.rs` checks it against the `@group`/`@binding` declarations naga reflects from
//! the WGSL (`shaders/render_bindings.wgsl` for groups 0–2, each pass for its group 3).

use std::sync::OnceLock;

use crate::formats::{DEPTH_FORMAT, VISIBLE_ID_FORMAT};
use crate::shaders::{self, BlockSpace, ObjectVariant, Shader};

/// One binding of a bind group: the WGSL global it feeds, its `@binding` and what is bound.
#[derive(Debug, Clone, Copy)]
pub struct Slot {
    /// Name of the WGSL global variable.
    pub wgsl_name: &'static str,
    /// Its `@binding` index.
    pub binding: u32,
    /// The stages that may use it.
    pub visibility: wgpu::ShaderStages,
    /// What is bound.
    pub ty: wgpu::BindingType,
}

impl Slot {
    /// The bind group layout entry, with the render passes' blocks in `space`.
    #[must_use]
    pub fn layout_entry(&self, space: BlockSpace) -> wgpu::BindGroupLayoutEntry {
        wgpu::BindGroupLayoutEntry {
            binding: self.binding,
            visibility: self.visibility,
            ty: space.binding_type(self.wgsl_name, self.ty),
            count: None,
        }
    }

    /// The bind group entry binding `resource` here.
    #[must_use]
    pub const fn entry<'a>(&self, resource: wgpu::BindingResource<'a>) -> wgpu::BindGroupEntry<'a> {
        wgpu::BindGroupEntry {
            binding: self.binding,
            resource,
        }
    }
}

/// One bind group: its `@group` index and its slots.
#[derive(Debug, Clone, Copy)]
pub struct BindGroupSpec {
    /// Label of the layout and of the groups made from it.
    pub label: &'static str,
    /// The `@group` index.
    pub index: u32,
    /// Its bindings.
    pub slots: &'static [Slot],
}

impl BindGroupSpec {
    /// Creates the bind group layout (the blocks in the device's [`BlockSpace`]).
    #[must_use]
    pub fn create_layout(&self, device: &wgpu::Device) -> wgpu::BindGroupLayout {
        let space = BlockSpace::of(device);
        let entries: Vec<wgpu::BindGroupLayoutEntry> = self
            .slots
            .iter()
            .map(|slot| slot.layout_entry(space))
            .collect();
        device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(self.label),
            entries: &entries,
        })
    }
}

/// A pipeline as its bindings see it: shader, entry points and bind groups (the group at
/// position i of `groups` has index i), for reflection against the WGSL.
#[derive(Debug, Clone)]
pub struct PipelineSpec {
    /// The pipeline's label.
    pub label: &'static str,
    /// Its shader.
    pub shader: Shader,
    /// Its entry points.
    pub entry_points: &'static [&'static str],
    /// Its bind groups, by index.
    pub groups: Vec<BindGroupSpec>,
}

/// Shader stages of the resources every pass reads.
const ALL_STAGES: wgpu::ShaderStages =
    wgpu::ShaderStages::VERTEX_FRAGMENT.union(wgpu::ShaderStages::COMPUTE);

/// A uniform buffer: for the probes' parameters. The render passes read their per-frame,
/// per-object and per-part values from read-only storage buffers instead, uniforms only on the
/// GL backend ([`crate::shaders::BlockSpace`] says why; `tests/reflect.rs` checks both).
pub const UNIFORM: wgpu::BindingType = wgpu::BindingType::Buffer {
    ty: wgpu::BufferBindingType::Uniform,
    has_dynamic_offset: false,
    min_binding_size: None,
};

/// A storage buffer, read-only or not.
#[must_use]
pub const fn storage(read_only: bool) -> wgpu::BindingType {
    wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only },
        has_dynamic_offset: false,
        min_binding_size: None,
    }
}

/// A 2D float texture read with `textureLoad` (no sampler: every filter is computed in the shader).
pub const TEXTURE_2D: wgpu::BindingType = wgpu::BindingType::Texture {
    sample_type: wgpu::TextureSampleType::Float { filterable: false },
    view_dimension: wgpu::TextureViewDimension::D2,
    multisampled: false,
};

/// The bindings of the render passes, by WGSL name.
pub mod slots {
    use super::{ALL_STAGES, Slot, TEXTURE_2D, storage};
    use wgpu::ShaderStages;

    /// Group 0: `frame_uniforms`.
    pub const FRAME_UNIFORMS: Slot = Slot {
        wgsl_name: "frame_uniforms",
        binding: 0,
        visibility: ALL_STAGES,
        ty: storage(true),
    };
    /// Group 0: `lut_table`, the colour table.
    pub const LUT_TABLE: Slot = Slot {
        wgsl_name: "lut_table",
        binding: 1,
        visibility: ALL_STAGES,
        ty: TEXTURE_2D,
    };
    /// Group 1: `object`, the object's uniforms.
    pub const OBJECT: Slot = Slot {
        wgsl_name: "object",
        binding: 0,
        visibility: ALL_STAGES,
        ty: storage(true),
    };
    /// Group 2: `part`, the part's uniforms.
    pub const PART: Slot = Slot {
        wgsl_name: "part",
        binding: 0,
        visibility: ALL_STAGES,
        ty: storage(true),
    };
    /// Group 2: `vertices`.
    pub const VERTICES: Slot = Slot {
        wgsl_name: "vertices",
        binding: 1,
        visibility: ALL_STAGES,
        ty: storage(true),
    };
    /// Group 2: `indices`.
    pub const INDICES: Slot = Slot {
        wgsl_name: "indices",
        binding: 2,
        visibility: ALL_STAGES,
        ty: storage(true),
    };
    /// Group 2: `part_texture`.
    pub const PART_TEXTURE: Slot = Slot {
        wgsl_name: "part_texture",
        binding: 3,
        visibility: ShaderStages::FRAGMENT,
        ty: TEXTURE_2D,
    };
    /// Group 3 of the proxy pass: `footprints`, written.
    pub const PROXY_FOOTPRINTS: Slot = Slot {
        wgsl_name: "footprints",
        binding: 0,
        visibility: ShaderStages::COMPUTE,
        ty: storage(false),
    };
    /// Group 3 of the proxy pass: `frame_bound`, the frame's screen bound, grown by every
    /// footprint (one buffer for every part).
    pub const PROXY_FRAME_BOUND: Slot = Slot {
        wgsl_name: "frame_bound",
        binding: 1,
        visibility: ShaderStages::COMPUTE,
        ty: storage(false),
    };
    /// Group 3 of the proxy pass: `draw_args`, the part's indirect draw arguments and screen
    /// bound.
    pub const PROXY_DRAW_ARGS: Slot = Slot {
        wgsl_name: "draw_args",
        binding: 2,
        visibility: ShaderStages::COMPUTE,
        ty: storage(false),
    };
    /// Group 3 of the LRT pass: `part_draw_args`, the proxy pass's `draw_args`, whose screen
    /// bound the shading pass draws.
    pub const LRT_DRAW_ARGS: Slot = Slot {
        wgsl_name: "part_draw_args",
        binding: 2,
        visibility: ShaderStages::VERTEX,
        ty: storage(true),
    };
    /// Group 0 of the LRT part-depth and shading passes: `frame_bound`, the proxy pass's frame
    /// screen bound, which the part-depth pass draws.
    pub const FRAME_BOUND: Slot = Slot {
        wgsl_name: "frame_bound",
        binding: 13,
        visibility: ShaderStages::VERTEX,
        ty: storage(true),
    };
    /// Group 3 of the LRT pass: `footprints`, read.
    pub const LRT_FOOTPRINTS: Slot = Slot {
        wgsl_name: "footprints",
        binding: 0,
        visibility: ShaderStages::VERTEX,
        ty: storage(true),
    };
    /// Group 0 of the LRT shading pass: `visible_ids`, the visibility pass's id target.
    pub const VISIBLE_IDS: Slot = Slot {
        wgsl_name: "visible_ids",
        binding: 2,
        visibility: ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Uint,
            view_dimension: wgpu::TextureViewDimension::D2,
            multisampled: false,
        },
    };
    /// Group 1 of the sky passes: `sky`, the sky's uniforms.
    pub const SKY: Slot = Slot {
        wgsl_name: "sky",
        binding: 0,
        visibility: ShaderStages::COMPUTE.union(ShaderStages::FRAGMENT),
        ty: storage(true),
    };
    /// Group 1 of the sky's compose pass: `sky_image`, the equirectangular sky image.
    pub const SKY_IMAGE: Slot = Slot {
        wgsl_name: "sky_image",
        binding: 4,
        visibility: ShaderStages::FRAGMENT,
        ty: TEXTURE_2D,
    };
    /// Group 1 of the sky's star pass: `stars`.
    pub const STARS: Slot = Slot {
        wgsl_name: "stars",
        binding: 1,
        visibility: ShaderStages::COMPUTE,
        ty: storage(true),
    };
    /// Group 1 of the sky's star pass: `star_light`, the star light per pixel, added to.
    pub const STAR_LIGHT: Slot = Slot {
        wgsl_name: "star_light",
        binding: 2,
        visibility: ShaderStages::COMPUTE,
        ty: storage(false),
    };
    /// Group 1 of the sky's compose pass: `star_light_total`, the same buffer, read.
    pub const STAR_LIGHT_TOTAL: Slot = Slot {
        wgsl_name: "star_light_total",
        binding: 3,
        visibility: ShaderStages::FRAGMENT,
        ty: storage(true),
    };
    /// Group 0 of the shading passes: `spectral_tables`, the Jakob–Hanika table of spectral
    /// colour ([`crate::spectral::spectral_words`]).
    pub const SPECTRAL_TABLES: Slot = Slot {
        wgsl_name: "spectral_tables",
        binding: 8,
        visibility: ShaderStages::FRAGMENT,
        ty: storage(true),
    };
    /// Group 0 of the shading passes: `spectral_cie`, the CIE 1931 table of spectral colour
    /// ([`crate::spectral::cie_texels`]).
    pub const SPECTRAL_CIE: Slot = Slot {
        wgsl_name: "spectral_cie",
        binding: 9,
        visibility: ShaderStages::FRAGMENT,
        ty: TEXTURE_2D,
    };
    /// Group 0 of the shading passes: `shadow_scene`, every object's BVH for the shadows of
    /// moving lights ([`crate::shadows`]).
    pub const SHADOW_SCENE: Slot = Slot {
        wgsl_name: "shadow_scene",
        binding: 12,
        visibility: ShaderStages::FRAGMENT,
        ty: storage(true),
    };
    /// Group 3 of the ray tracer's visibility pass: `bvh_nodes`, the object's BVH.
    pub const BVH_NODES: Slot = Slot {
        wgsl_name: "bvh_nodes",
        binding: 3,
        visibility: ShaderStages::FRAGMENT,
        ty: storage(true),
    };
    /// Group 3 of the ray tracer's visibility pass: `bvh_triangles`, the object's triangles in
    /// leaf order.
    pub const BVH_TRIANGLES: Slot = Slot {
        wgsl_name: "bvh_triangles",
        binding: 4,
        visibility: ShaderStages::FRAGMENT,
        ty: storage(true),
    };
    /// Group 3 of the LRT pass: `fragment_count`.
    pub const FRAGMENT_COUNT: Slot = Slot {
        wgsl_name: "fragment_count",
        binding: 1,
        visibility: ShaderStages::FRAGMENT,
        ty: storage(false),
    };
    /// Group 3 of the image-based look-up: `ib_cube`, the velocity group's cube map (a 2D
    /// array of six layers, one per face, read with `textureLoad`).
    pub const IB_CUBE: Slot = Slot {
        wgsl_name: "ib_cube",
        binding: 0,
        visibility: ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: wgpu::TextureViewDimension::D2Array,
            multisampled: false,
        },
    };
}

/// Group 0: frame uniforms and colour table.
pub const FRAME_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt frame",
    index: 0,
    slots: &[slots::FRAME_UNIFORMS, slots::LUT_TABLE],
};
/// Group 0 of the LRT part-depth and shading passes: the frame group, the visibility pass's ids
/// (a separate layout, because the visibility pass renders into the ids while group 0 is
/// bound), the spectral tables, the lights with the shadow casters and the frame's screen bound.
pub const SHADE_FRAME_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt frame (shading)",
    index: 0,
    slots: &[
        slots::FRAME_UNIFORMS,
        slots::LUT_TABLE,
        slots::VISIBLE_IDS,
        slots::SPECTRAL_TABLES,
        slots::SPECTRAL_CIE,
        slots::SHADOW_SCENE,
        slots::FRAME_BOUND,
    ],
};
/// Group 0 of the polygon pass: the frame group, the spectral tables and the lights with the
/// shadow casters.
pub const POLYGON_FRAME_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt frame (polygon)",
    index: 0,
    slots: &[
        slots::FRAME_UNIFORMS,
        slots::LUT_TABLE,
        slots::SPECTRAL_TABLES,
        slots::SPECTRAL_CIE,
        slots::SHADOW_SCENE,
    ],
};
/// Group 0 of the sky's compose pass: the frame group and the spectral tables.
pub const SKY_FRAME_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt frame (sky)",
    index: 0,
    slots: &[
        slots::FRAME_UNIFORMS,
        slots::LUT_TABLE,
        slots::SPECTRAL_TABLES,
        slots::SPECTRAL_CIE,
    ],
};
/// Group 1: object uniforms.
pub const OBJECT_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt object",
    index: 1,
    slots: &[slots::OBJECT],
};
/// Group 2: part uniforms, vertices, indices, texture (filtered in the shader: surface.wgsl).
pub const PART_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt part",
    index: 2,
    slots: &[
        slots::PART,
        slots::VERTICES,
        slots::INDICES,
        slots::PART_TEXTURE,
    ],
};
/// Group 3 of the proxy pass: footprints, the frame's screen bound and the part's draw arguments
/// with its screen bound, written.
pub const PROXY_OUTPUT_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt proxy output",
    index: 3,
    slots: &[
        slots::PROXY_FOOTPRINTS,
        slots::PROXY_FRAME_BOUND,
        slots::PROXY_DRAW_ARGS,
    ],
};
/// Group 3 of the LRT passes: footprints (read), the fragment counter and the part's draw
/// arguments with its screen bound (read).
pub const LRT_INPUT_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt lrt input",
    index: 3,
    slots: &[
        slots::LRT_FOOTPRINTS,
        slots::FRAGMENT_COUNT,
        slots::LRT_DRAW_ARGS,
    ],
};
/// Group 3 of the ray tracer's visibility pass: the footprints of the object's box (read), the
/// fragment counter and the object's BVH with its triangles.
pub const RT_INPUT_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt rt input",
    index: 3,
    slots: &[
        slots::LRT_FOOTPRINTS,
        slots::FRAGMENT_COUNT,
        slots::BVH_NODES,
        slots::BVH_TRIANGLES,
    ],
};

/// Group 3 of the image-based look-up: the velocity group's cube map.
pub const IB_CUBE_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt image-based cube map",
    index: 3,
    slots: &[slots::IB_CUBE],
};

/// Group 1 of the sky's star pass: the sky's uniforms, its stars and the star light, written.
pub const SKY_STARS_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt sky stars",
    index: 1,
    slots: &[slots::SKY, slots::STARS, slots::STAR_LIGHT],
};
/// Group 1 of the sky's compose pass: the sky's uniforms, the star light (read) and the sky
/// image.
pub const SKY_COMPOSE_GROUP: BindGroupSpec = BindGroupSpec {
    label: "srt sky compose",
    index: 1,
    slots: &[slots::SKY, slots::STAR_LIGHT_TOTAL, slots::SKY_IMAGE],
};

/// Entry points of the sky's star passes, in the order they run: each pixel's peak, then the
/// star light scaled to it (sky.wgsl).
pub const SKY_STARS_ENTRIES: [&str; 2] = ["sky_star_peaks", "sky_stars"];
/// Entry points of the sky's compose pass (vertex, fragment).
pub const SKY_COMPOSE_ENTRIES: [&str; 2] = ["sky_compose_vertex", "sky_compose"];
/// Entry points of the sky's compose triangle drawn in the polygon pass, behind its objects.
pub const SKY_BEHIND_POLYGONS_ENTRIES: [&str; 2] = ["sky_behind_polygons_vertex", "sky_compose"];
/// Entry points of the sky's compose triangle drawn in the exact shading pass, where no part is
/// seen.
pub const SKY_WHERE_UNSEEN_ENTRIES: [&str; 2] = ["sky_where_unseen_vertex", "sky_compose"];

/// The sky's two pipelines as their bindings see them: the stars' compute pass and the
/// background pass (whose group 0 carries the spectral tables).
#[must_use]
pub fn sky_specs() -> [PipelineSpec; 2] {
    [
        PipelineSpec {
            label: "srt sky stars",
            shader: shaders::sky(),
            entry_points: &SKY_STARS_ENTRIES,
            groups: vec![FRAME_GROUP, SKY_STARS_GROUP],
        },
        PipelineSpec {
            label: "srt sky compose",
            shader: shaders::sky(),
            entry_points: &SKY_COMPOSE_ENTRIES,
            groups: vec![SKY_FRAME_GROUP, SKY_COMPOSE_GROUP],
        },
    ]
}

/// Entry point of the proxy pass.
const PROXY_ENTRY: &str = "footprint_main";
/// Entry points of the LRT visibility pass: vertex and fragment with flat varyings, then with
/// lean ones ([`Varyings::pick`]).
const LRT_VISIBILITY_ENTRIES: [&str; 4] = [
    "lrt_vertex",
    shaders::VISIBILITY_FRAGMENT_ENTRIES[0],
    "lrt_vertex_lean",
    shaders::VISIBILITY_FRAGMENT_ENTRIES[1],
];
/// Entry points of the LRT shading pass, as [`LRT_VISIBILITY_ENTRIES`].
const LRT_SHADE_ENTRIES: [&str; 4] = [
    "part_bound_vertex",
    "lrt_shade",
    "part_bound_vertex_lean",
    "lrt_shade_lean",
];
/// Entry points of the LRT part-depth pass (vertex, fragment).
const PART_DEPTH_ENTRIES: [&str; 2] = ["id_depth_vertex", "id_depth"];
/// Entry points of the ray tracer's visibility pass, as [`LRT_VISIBILITY_ENTRIES`].
const RT_VISIBILITY_ENTRIES: [&str; 4] = [
    "box_vertex",
    shaders::VISIBILITY_FRAGMENT_ENTRIES[2],
    "box_vertex_lean",
    shaders::VISIBILITY_FRAGMENT_ENTRIES[3],
];

/// How the object passes (LRT's visibility and shading, the ray tracer's visibility) hand a
/// draw's data — the camera, the object's frame, the triangle's corners — from the vertex to
/// the fragment stage (lrt.wgsl's `LrtVarying` and `LeanVarying`). The images are the same bit
/// for bit; the speed is not.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Varyings {
    /// As flat varyings, read once per vertex: Mesa's llvmpipe reads a storage buffer in a
    /// fragment shader one lane at a time, and those reads were most of an LRT visibility
    /// fragment (docs/performance-log.md, 2026-11-27, fourth entry).
    Flat,
    /// Only the triangle and the part's id; each fragment reads the rest. A hardware GPU pays
    /// for every varying of every footprint vertex: on an H200 the flat varyings took LRT's
    /// sustained rate on the nine engines at 1920×1080 from 77.5 to 33.8 frames per second
    /// (docs/performance-log.md, 2026-11-27, sixth entry).
    Lean,
}

impl Varyings {
    /// What suits an adapter of `device_type`: flat on a CPU adapter, lean on any other.
    #[must_use]
    pub fn for_adapter(device_type: wgpu::DeviceType) -> Self {
        if device_type == wgpu::DeviceType::Cpu {
            Self::Flat
        } else {
            Self::Lean
        }
    }

    /// The (vertex, fragment) pair of `entries` for these varyings.
    const fn pick(
        self,
        [flat_vertex, flat_fragment, lean_vertex, lean_fragment]: [&'static str; 4],
    ) -> [&'static str; 2] {
        match self {
            Self::Flat => [flat_vertex, flat_fragment],
            Self::Lean => [lean_vertex, lean_fragment],
        }
    }
}
/// Entry points of the polygon pass (vertex, fragment).
const POLYGON_ENTRIES: [&str; 2] = ["polygon_vertex", "polygon_fragment"];

/// Entry points of the image-based method's face passes (vertex, fragment).
const IB_FACE_ENTRIES: [&str; 2] = ["ib_face_vertex", "ib_face_fragment"];
/// Entry points of the image-based method's look-up pass (vertex, fragment).
const IB_LOOKUP_ENTRIES: [&str; 2] = ["ib_lookup_vertex", "ib_lookup_fragment"];

/// The image-based method's two pipelines as their bindings see them, compiled for `variant`:
/// the cube map's faces (the polygon pass's groups) and the look-up (with the cube map as
/// group 3; the part group is bound but not read).
#[must_use]
pub fn image_based_specs(variant: ObjectVariant) -> [PipelineSpec; 2] {
    let variant = ObjectVariant {
        counting: false,
        ..variant
    };
    let groups = vec![POLYGON_FRAME_GROUP, OBJECT_GROUP, PART_GROUP];
    [
        PipelineSpec {
            label: "srt image-based faces",
            shader: shaders::image_based(variant),
            entry_points: &IB_FACE_ENTRIES,
            groups: groups.clone(),
        },
        PipelineSpec {
            label: "srt image-based look-up",
            shader: shaders::image_based(variant),
            entry_points: &IB_LOOKUP_ENTRIES,
            groups: [&groups[..], &[IB_CUBE_GROUP]].concat(),
        },
    ]
}

/// The image-based method's pipelines for one [`ObjectVariant`].
pub struct ImageBasedPipelines {
    /// Draws a part into one face of the cube map (its colour format, the reversed depth test).
    pub face: wgpu::RenderPipeline,
    /// Draws a velocity group's light into the colour target, its apparent distance as depth.
    pub lookup: wgpu::RenderPipeline,
}

/// The six pipelines of the renderer as their bindings see them: proxy, LRT visibility, LRT
/// shading, ray-tracer visibility (the three with the fragment counter when `counting`),
/// polygon, and the LRT part-depth pass between visibility and shading; all compiled for
/// `variant` ([`ObjectVariant`]; the polygon pass never counts).
#[must_use]
pub fn specs(variant: ObjectVariant) -> [PipelineSpec; 6] {
    let base = [FRAME_GROUP, OBJECT_GROUP, PART_GROUP];
    [
        PipelineSpec {
            label: "srt proxy",
            shader: shaders::proxy(),
            entry_points: &[PROXY_ENTRY],
            groups: [&base[..], &[PROXY_OUTPUT_GROUP]].concat(),
        },
        PipelineSpec {
            label: "srt lrt visibility",
            shader: shaders::lrt(variant),
            entry_points: &LRT_VISIBILITY_ENTRIES,
            groups: [&base[..], &[LRT_INPUT_GROUP]].concat(),
        },
        PipelineSpec {
            label: "srt lrt shading",
            shader: shaders::lrt(variant),
            entry_points: &LRT_SHADE_ENTRIES,
            groups: vec![SHADE_FRAME_GROUP, OBJECT_GROUP, PART_GROUP, LRT_INPUT_GROUP],
        },
        PipelineSpec {
            label: "srt rt visibility",
            shader: shaders::lrt(variant),
            entry_points: &RT_VISIBILITY_ENTRIES,
            groups: [&base[..], &[RT_INPUT_GROUP]].concat(),
        },
        PipelineSpec {
            label: "srt polygon",
            shader: shaders::polygon(ObjectVariant {
                counting: false,
                ..variant
            }),
            entry_points: &POLYGON_ENTRIES,
            groups: vec![POLYGON_FRAME_GROUP, OBJECT_GROUP, PART_GROUP],
        },
        PipelineSpec {
            label: "srt lrt part depth",
            shader: shaders::lrt(variant),
            entry_points: &PART_DEPTH_ENTRIES,
            groups: vec![SHADE_FRAME_GROUP],
        },
    ]
}

/// The visibility pipelines of the two exact methods, local ray tracing and the ray tracer, for
/// one [`ObjectVariant::for_visibility`].
pub struct VisibilityPipelines {
    /// Nearest hit per pixel by footprints: depth and id.
    pub visibility: wgpu::RenderPipeline,
    /// Nearest hit per pixel through each batch's BVH: depth and id.
    pub rt_visibility: wgpu::RenderPipeline,
}

impl VisibilityPipelines {
    fn new(
        device: &wgpu::Device,
        [_, visibility, _, rt_visibility, ..]: &[PipelineSpec; 6],
        varyings: Varyings,
    ) -> Self {
        Self {
            visibility: render_pipeline(
                device,
                visibility,
                varyings.pick(LRT_VISIBILITY_ENTRIES),
                Some(VISIBLE_ID_FORMAT),
                DepthTest::Nearest,
            ),
            rt_visibility: render_pipeline(
                device,
                rt_visibility,
                varyings.pick(RT_VISIBILITY_ENTRIES),
                Some(VISIBLE_ID_FORMAT),
                DepthTest::Nearest,
            ),
        }
    }
}

/// The bind group layouts and pipelines, created once per device.
pub struct Pipelines {
    /// Layout of [`FRAME_GROUP`].
    pub frame_layout: wgpu::BindGroupLayout,
    /// Layout of [`OBJECT_GROUP`].
    pub object_layout: wgpu::BindGroupLayout,
    /// Layout of [`PART_GROUP`].
    pub part_layout: wgpu::BindGroupLayout,
    /// Layout of [`PROXY_OUTPUT_GROUP`].
    pub proxy_output_layout: wgpu::BindGroupLayout,
    /// Layout of [`LRT_INPUT_GROUP`].
    pub lrt_input_layout: wgpu::BindGroupLayout,
    /// Layout of [`RT_INPUT_GROUP`].
    pub rt_input_layout: wgpu::BindGroupLayout,
    /// Layout of [`SHADE_FRAME_GROUP`].
    pub shade_frame_layout: wgpu::BindGroupLayout,
    /// Layout of [`POLYGON_FRAME_GROUP`].
    pub polygon_frame_layout: wgpu::BindGroupLayout,
    /// Layout of [`SKY_FRAME_GROUP`].
    pub sky_frame_layout: wgpu::BindGroupLayout,
    /// The footprint compute pipeline.
    pub proxy: wgpu::ComputePipeline,
    /// The exact methods' visibility pipelines, by [`ObjectVariant::index`] of
    /// [`ObjectVariant::for_visibility`]; the shading pipelines (one shading per pixel: each
    /// part's bound at the part's depth, tested for equality) and the polygon pipelines, by
    /// [`ObjectVariant::index`]. Each is made when first asked for, so that a renderer compiles
    /// only the variants its frames draw (on a software adapter a pipeline of the object passes
    /// takes a noticeable part of a second to compile).
    visibility: Vec<std::sync::OnceLock<VisibilityPipelines>>,
    shade: Vec<std::sync::OnceLock<wgpu::RenderPipeline>>,
    polygon: Vec<std::sync::OnceLock<wgpu::RenderPipeline>>,
    image_based: Vec<std::sync::OnceLock<ImageBasedPipelines>>,
    /// The depth of the part kept at each pixel, which the shading pass tests (the same for
    /// every variant).
    pub part_depth: wgpu::RenderPipeline,
    /// The colour format the render pipelines draw into.
    color_format: wgpu::TextureFormat,
    /// Whether the shading passes draw moving lights.
    lit: bool,
    /// How the object passes carry a draw's data to their fragments.
    varyings: Varyings,
}

impl Pipelines {
    /// Creates the layouts and the proxy and part-depth pipelines on `device` (the object passes'
    /// come on first use), rendering into `color_format`, the shading passes with moving lights
    /// where `lit` ([`shaders::lrt`]), the object passes with `varyings`.
    /// Each pipeline's layout is made from its [`PipelineSpec`]; bind group layouts with the same
    /// entries are interchangeable (WebGPU's group equivalence), so the bind groups made with
    /// the layouts kept here fit every pipeline.
    #[must_use]
    pub fn new(
        device: &wgpu::Device,
        color_format: wgpu::TextureFormat,
        lit: bool,
        varyings: Varyings,
    ) -> Self {
        let plain = ObjectVariant {
            lit,
            ..ObjectVariant::PLAIN
        };
        let specs = specs(plain);
        let [proxy_spec, .., part_depth_spec] = &specs;
        let proxy_module = proxy_spec.shader.module(device);
        let proxy = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(proxy_spec.label),
            layout: Some(&pipeline_layout(device, proxy_spec)),
            module: &proxy_module,
            entry_point: Some(PROXY_ENTRY),
            compilation_options: proxy_spec.shader.compilation_options(),
            cache: None,
        });
        Self {
            frame_layout: FRAME_GROUP.create_layout(device),
            object_layout: OBJECT_GROUP.create_layout(device),
            part_layout: PART_GROUP.create_layout(device),
            proxy_output_layout: PROXY_OUTPUT_GROUP.create_layout(device),
            lrt_input_layout: LRT_INPUT_GROUP.create_layout(device),
            rt_input_layout: RT_INPUT_GROUP.create_layout(device),
            shade_frame_layout: SHADE_FRAME_GROUP.create_layout(device),
            polygon_frame_layout: POLYGON_FRAME_GROUP.create_layout(device),
            sky_frame_layout: SKY_FRAME_GROUP.create_layout(device),
            proxy,
            visibility: (0..ObjectVariant::COUNT).map(|_| OnceLock::new()).collect(),
            shade: (0..ObjectVariant::COUNT).map(|_| OnceLock::new()).collect(),
            polygon: (0..ObjectVariant::COUNT).map(|_| OnceLock::new()).collect(),
            image_based: (0..ObjectVariant::COUNT).map(|_| OnceLock::new()).collect(),
            part_depth: render_pipeline(
                device,
                part_depth_spec,
                PART_DEPTH_ENTRIES,
                None,
                DepthTest::Overwrite,
            ),
            color_format,
            lit,
            varyings,
        }
    }

    /// The visibility pipelines for objects drawn as `variant` (whose `lit` must be the
    /// renderer's), created on first use.
    pub fn visibility(
        &self,
        device: &wgpu::Device,
        variant: ObjectVariant,
    ) -> &VisibilityPipelines {
        debug_assert_eq!(variant.lit, self.lit, "the renderer's moving lights");
        let variant = variant.for_visibility();
        self.visibility[variant.index()]
            .get_or_init(|| VisibilityPipelines::new(device, &specs(variant), self.varyings))
    }

    /// The LRT shading pipeline for parts drawn as `variant` (whose `lit` must be the
    /// renderer's), created on first use.
    pub fn shade(&self, device: &wgpu::Device, variant: ObjectVariant) -> &wgpu::RenderPipeline {
        debug_assert_eq!(variant.lit, self.lit, "the renderer's moving lights");
        self.shade[variant.index()].get_or_init(|| {
            let [_, _, shade_spec, ..] = &specs(variant);
            render_pipeline(
                device,
                shade_spec,
                self.varyings.pick(LRT_SHADE_ENTRIES),
                Some(self.color_format),
                DepthTest::Equal,
            )
        })
    }

    /// The polygon pipeline for parts drawn as `variant` (whose `lit` must be the renderer's;
    /// it never counts), created on first use.
    pub fn polygon(&self, device: &wgpu::Device, variant: ObjectVariant) -> &wgpu::RenderPipeline {
        debug_assert_eq!(variant.lit, self.lit, "the renderer's moving lights");
        let variant = ObjectVariant {
            counting: false,
            ..variant
        };
        self.polygon[variant.index()].get_or_init(|| {
            let [.., polygon_spec, _] = &specs(variant);
            render_pipeline(
                device,
                polygon_spec,
                POLYGON_ENTRIES,
                Some(self.color_format),
                DepthTest::Nearest,
            )
        })
    }

    /// The image-based method's pipelines for parts drawn as `variant` (whose `lit` must be the
    /// renderer's; they never count), created on first use. The cube map has the colour
    /// target's format.
    pub fn image_based(
        &self,
        device: &wgpu::Device,
        variant: ObjectVariant,
    ) -> &ImageBasedPipelines {
        debug_assert_eq!(variant.lit, self.lit, "the renderer's moving lights");
        let variant = ObjectVariant {
            counting: false,
            ..variant
        };
        self.image_based[variant.index()].get_or_init(|| {
            let [face, lookup] = &image_based_specs(variant);
            ImageBasedPipelines {
                face: render_pipeline(
                    device,
                    face,
                    IB_FACE_ENTRIES,
                    Some(self.color_format),
                    DepthTest::Farthest,
                ),
                lookup: render_pipeline(
                    device,
                    lookup,
                    IB_LOOKUP_ENTRIES,
                    Some(self.color_format),
                    DepthTest::Nearest,
                ),
            }
        })
    }

    /// Whether the shading passes draw moving lights (every variant's `lit`).
    #[must_use]
    pub fn lit(&self) -> bool {
        self.lit
    }
}

/// The pipeline layout of `spec`: one bind group layout per group, in index order.
pub(crate) fn pipeline_layout(device: &wgpu::Device, spec: &PipelineSpec) -> wgpu::PipelineLayout {
    let layouts: Vec<wgpu::BindGroupLayout> = spec
        .groups
        .iter()
        .map(|group| group.create_layout(device))
        .collect();
    let layouts: Vec<Option<&wgpu::BindGroupLayout>> = layouts.iter().map(Some).collect();
    device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(spec.label),
        bind_group_layouts: &layouts,
        immediate_size: 0,
    })
}

/// The depth test of a render pipeline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum DepthTest {
    /// No depth attachment.
    None,
    /// The nearer fragment wins and writes its depth (visibility passes, polygon).
    Nearest,
    /// Only fragments at the depth already there pass, before the fragment shader; nothing is
    /// written (LRT shading at the part's depth).
    Equal,
    /// Every fragment writes its depth, whatever was there (LRT's part-depth pass).
    Overwrite,
    /// The fragment of larger depth wins and writes it (the image-based faces' reversed depth,
    /// near / z).
    Farthest,
}

impl DepthTest {
    /// The pipeline's depth-stencil state.
    fn state(self) -> Option<wgpu::DepthStencilState> {
        let (write, compare) = match self {
            Self::None => return None,
            Self::Nearest => (true, wgpu::CompareFunction::Less),
            Self::Equal => (false, wgpu::CompareFunction::Equal),
            Self::Overwrite => (true, wgpu::CompareFunction::Always),
            Self::Farthest => (true, wgpu::CompareFunction::Greater),
        };
        Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(write),
            depth_compare: Some(compare),
            stencil: wgpu::StencilState::default(),
            bias: wgpu::DepthBiasState::default(),
        })
    }
}

/// The render pipeline of `spec` with its `vertex` and `fragment` entry points, drawing into
/// `color_format` (none: depth only), with the depth test `depth`.
pub(crate) fn render_pipeline(
    device: &wgpu::Device,
    spec: &PipelineSpec,
    [vertex, fragment]: [&str; 2],
    color_format: Option<wgpu::TextureFormat>,
    depth: DepthTest,
) -> wgpu::RenderPipeline {
    let module = spec.shader.module(device);
    let targets: Vec<Option<wgpu::ColorTargetState>> = color_format
        .map(|format| wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::ALL,
        })
        .into_iter()
        .map(Some)
        .collect();
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.label),
        layout: Some(&pipeline_layout(device, spec)),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some(vertex),
            compilation_options: spec.shader.compilation_options(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: None,
            ..Default::default()
        },
        depth_stencil: depth.state(),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some(fragment),
            compilation_options: spec.shader.compilation_options(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}
