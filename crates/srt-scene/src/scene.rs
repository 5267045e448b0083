//! The scene model: moving objects, the observer and the light (both at rest in S), shading
//! parameters and the effect mode. S is the observer's rest frame: a scene file whose observer
//! moves through its world frame is brought into S by
//! [`SceneDescription::build`](crate::SceneDescription::build).

use crate::projection::{Projection, Stereo};
use crate::sky::Sky;
use glam::dcamera::rh::proj::directx::perspective;
use glam::dcamera::rh::view::look_to_mat4;
use glam::{DMat4, DVec2, DVec3};
use srt_color::{RadianceScale, RadianceTable, ToneMap};
use srt_physics::motion::Motion;
use srt_physics::{Event, Frame, Poincare, RelativeFrame};

use crate::mesh::Part;

/// Which relativistic effects the colours show (the paper's toggles, §3.3 and Fig. 6–7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Effects {
    /// Geometry only (aberration, light travel time): Doppler factor forced to 1.
    Geometry,
    /// Doppler colour shift with brightness normalised away (Fig. 6 left).
    #[default]
    Doppler,
    /// Doppler shift and searchlight (intensity) effect (Fig. 6 right).
    Searchlight,
}

crate::choice!(Effects, "effect mode", {
    Geometry => "geometry", "geometry only: aberration and light travel time, no colour shift";
    Doppler => "doppler", "Doppler colour shift, brightness normalised (Fig. 6 left)";
    Searchlight => "searchlight", "Doppler shift and searchlight effect (Fig. 6 right)";
});

impl Effects {
    /// The colour table this mode uses unless the scene overrides it.
    #[must_use]
    pub const fn default_tone_map(self) -> ToneMap {
        match self {
            Self::Geometry | Self::Doppler => ToneMap::Luminance,
            Self::Searchlight => ToneMap::Searchlight,
        }
    }
}

/// How the colour of a lit surface is computed (docs/colour.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SurfaceColour {
    /// The paper's shortcut (§4.2, Eq. 18): the light's colour at D·T, scaled by the surface's
    /// grey value: a red and a blue surface shift alike.
    #[default]
    Paper,
    /// Every reflectance is a spectrum (Jakob & Hanika 2019), lit by the black body the surface
    /// sees (D_in·T) and shifted to the observer (D_out): colours move through the spectrum.
    Spectral,
}

crate::choice!(SurfaceColour, "surface colour", {
    Paper => "paper",
        "the paper's shortcut: the light's colour at D·T scaled by the surface's grey value";
    Spectral => "spectral",
        "reflectance spectra (Jakob & Hanika 2019) under the shifted black body: colours move";
});

/// A surface that glows as a black body, at rest in its object's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Emission {
    /// Black-body temperature in kelvin (> 0).
    pub temperature_k: f64,
    /// Brightness relative to the luminance tone map's white (≥ 0).
    pub brightness: f64,
    /// The glow switches on and off with the object's proper time (`None`: it glows always).
    pub blink: Option<Blink>,
}

impl Emission {
    /// Whether the surface glows at an event where its object's proper time is `proper_time`
    /// (ct′; [`Object::proper_time`]); where it does not, it reflects the light as any surface.
    #[must_use]
    pub fn shines_at(&self, proper_time: f64) -> bool {
        self.blink.is_none_or(|blink| blink.is_on(proper_time))
    }
}

/// A clock face drawn on every face of an object (`texture = { type = "clock", … }`): a dial with
/// twelve ticks, a slow and a fast hand and the reading in digits, in each triangle's texture
/// coordinates (one face per cube face). Each pixel shows the reading at the proper time of the
/// event it sees (docs/physics.md, "Time seen on a surface"); srt-trace's `clock` module draws it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clock {
    /// Reading per unit of proper time ct′.
    pub rate: f64,
    /// Reading at proper time 0.
    pub offset: f64,
    /// Reading per turn of the slow hand (the fast hand turns once per unit of reading).
    pub dial: f64,
    /// Colour of the face (sRGB-encoded, components in [0, 1], as a texel's).
    pub face: [f64; 3],
    /// Colour of the ring, ticks, hands and digits.
    pub ink: [f64; 3],
}

/// A clock's default reading per turn of the slow hand (a twelve-hour dial).
pub const DEFAULT_CLOCK_DIAL: f64 = 12.0;

/// A clock's default face and ink colours: off-white and near-black.
pub const DEFAULT_CLOCK_COLORS: [[f64; 3]; 2] = [[0.95, 0.93, 0.85], [0.05, 0.05, 0.1]];

impl Clock {
    /// What the clock shows at proper time `proper_time` (ct′).
    #[must_use]
    pub fn reading(&self, proper_time: f64) -> f64 {
        self.rate.mul_add(proper_time, self.offset)
    }
}

/// An emission's blinking, in the object's proper time: on for `duty` of each `period`, starting
/// at proper time 0 (on while (τ / period) mod 1 < duty).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Blink {
    /// One cycle, in proper time ct′ (scene units of length; > 0).
    pub period: f64,
    /// The fraction of each cycle the emission is on, in [0, 1].
    pub duty: f64,
}

impl Blink {
    /// Whether the emission is on at proper time `proper_time` (ct′).
    #[must_use]
    pub fn is_on(&self, proper_time: f64) -> bool {
        (proper_time / self.period).rem_euclid(1.0) < self.duty
    }
}

/// What an object's surfaces do beyond their reflectance colour.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceOptics {
    /// Reflectance below 380 nm (in [0, 1]), replacing the spectral model's extrapolation there.
    pub ultraviolet: Option<f64>,
    /// Reflectance above 780 nm (in [0, 1]), replacing the spectral model's extrapolation there.
    pub infrared: Option<f64>,
    /// The surfaces glow instead of reflecting the light.
    pub emission: Option<Emission>,
}

/// The observer: a camera at rest in S, looking at its observation time `time`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observer {
    /// Position in S.
    pub position: DVec3,
    /// Viewing direction (need not be normalised).
    pub direction: DVec3,
    /// Approximate up direction (made orthogonal to `direction`).
    pub up: DVec3,
    /// Vertical field of view in degrees, in (0, 180).
    pub fov_y_deg: f64,
    /// The observation time: the observer's own clock when it looks (the scene file's
    /// `observer.time`, or its `ct` where it gives none), which is the time of S (c = 1): the
    /// paper's ct_obs.
    pub time: f64,
    /// How the image maps its points to viewing directions ([`Projection`]).
    pub projection: Projection,
    /// Two eyes in one picture ([`Stereo`]; `None`: one eye at `position`).
    pub stereo: Option<Stereo>,
}

impl Observer {
    /// Whether a pixel's ray follows from its place in the whole picture — a wide projection
    /// or a stereo pair — rather than from one pinhole over the whole image: such pictures
    /// are traced, as the footprint methods draw through one pinhole. WGSL's
    /// `picture_decides` (camera.wgsl) is the GPU's twin.
    #[must_use]
    pub fn picture_decides(&self) -> bool {
        !self.projection.is_pinhole() || self.stereo.is_some()
    }

    /// The observation event (ct_obs, x_obs) in S.
    #[must_use]
    pub const fn event(&self) -> Event {
        Event::new(self.time, self.position)
    }

    /// Orthonormal camera basis (forward, right, up).
    #[must_use]
    pub fn basis(&self) -> (DVec3, DVec3, DVec3) {
        let forward = self.direction.normalize();
        let right = forward.cross(self.up).normalize();
        (forward, right, right.cross(forward))
    }

    /// The (unnormalised) viewing direction in S of the pinhole camera through the point `ndc`
    /// of normalised device coordinates (x right, y up, both in [−1, 1]) for an image of
    /// `aspect` = width / height, whatever the projection (the GPU's passes draw the pinhole's
    /// picture). Agrees with [`Observer::view_projection`].
    #[must_use]
    pub fn view_direction(&self, ndc: DVec2, aspect: f64) -> DVec3 {
        ViewRays {
            projection: Projection::Perspective,
            stereo: None,
            ..self.view_rays(aspect)
        }
        .pinhole(ndc)
    }

    /// The viewing directions of every point of an image of `aspect` = width / height in this
    /// observer's projection, computed once (the basis and the field of view's tangent).
    #[must_use]
    pub fn view_rays(&self, aspect: f64) -> ViewRays {
        let (forward, right, up) = self.basis();
        ViewRays {
            forward,
            right,
            up,
            tan_half: (0.5 * self.fov_y_deg.to_radians()).tan(),
            aspect,
            projection: self.projection,
            stereo: self.stereo,
        }
    }

    /// View-projection matrix (S → clip space; NDC depth in [0, 1], y up) for an image of
    /// `aspect` = width / height.
    #[must_use]
    pub fn view_projection(&self, aspect: f64, near: f64, far: f64) -> DMat4 {
        let (forward, _, up) = self.basis();
        perspective(self.fov_y_deg.to_radians(), aspect, near, far)
            * look_to_mat4(self.position, forward, up)
    }
}

/// The viewing directions of one observer's image ([`Observer::view_rays`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewRays {
    /// The observer's forward, right and up unit vectors.
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    /// tan(fov_y / 2).
    tan_half: f64,
    /// Width / height.
    aspect: f64,
    /// The observer's projection.
    projection: Projection,
    /// The observer's stereo pair, if any.
    stereo: Option<Stereo>,
}

impl ViewRays {
    /// The ray through the point `ndc` of normalised device coordinates (x right, y up, both
    /// in [−1, 1]) of the whole picture: the offset (in S) from the observer of the eye it
    /// leaves from (zero without stereo) and its (unnormalised) viewing direction; `None`
    /// where the picture sees nothing (outside a fisheye's circle). With stereo each eye's half
    /// is a picture of its own ([`Stereo::eye_at`]).
    #[must_use]
    pub fn ray(&self, ndc: DVec2) -> Option<(DVec3, DVec3)> {
        let Some(stereo) = self.stereo else {
            return self.direction(ndc).map(|d| (DVec3::ZERO, d));
        };
        let point = Stereo::eye_at(self.projection, ndc);
        let direction = self.eye_rays().direction(point.ndc)?;
        let basis = [self.forward, self.right, self.up];
        Some((stereo.eye_offset(self.projection, point, basis), direction))
    }

    /// Whether the picture holds a stereo pair.
    #[must_use]
    pub const fn is_stereo(&self) -> bool {
        self.stereo.is_some()
    }

    /// The direction through the point `step` (normalised device coordinates of the whole
    /// picture, a pixel's size) beyond `ndc`, from the same eye: for texture filtering (ray
    /// differentials). In a stereo picture the neighbour of a pixel at the edge of its eye's
    /// half lies beyond that half, in the eye's own picture, not in the other eye's half.
    #[must_use]
    pub fn neighbour(&self, ndc: DVec2, step: DVec2) -> Option<DVec3> {
        if self.stereo.is_none() {
            return self.direction(ndc + step);
        }
        let point = Stereo::eye_at(self.projection, ndc);
        // Each half is stretched over [−1, 1] along the axis the halves share.
        let stretch = if self.projection == Projection::Equirectangular {
            DVec2::new(1.0, 2.0)
        } else {
            DVec2::new(2.0, 1.0)
        };
        self.eye_rays().direction(point.ndc + step * stretch)
    }

    /// The points of the whole picture (normalised device coordinates) where a direction far
    /// away (a star: the same for both eyes) is seen: one without stereo, one in each eye's
    /// half with it; `None` where it is not in the picture.
    #[must_use]
    pub fn image_points(&self, direction: DVec3) -> [Option<DVec2>; 2] {
        if self.stereo.is_none() {
            return [self.image_point(direction), None];
        }
        let eye = self.eye_rays();
        [-1.0, 1.0].map(|side| {
            eye.image_point(direction)
                .map(|ndc| Stereo::picture_point(self.projection, side, ndc))
        })
    }

    /// The pictures a `width` × `height` picture is made of, each as (left, top, width,
    /// height) in pixels with the rays of that picture alone: the whole picture, or each eye's
    /// half of a stereo picture (left eye first; the split side is even,
    /// [`Stereo::check_size`]).
    #[must_use]
    pub fn eye_pictures(&self, width: u32, height: u32) -> Vec<([u32; 4], Self)> {
        if self.stereo.is_none() {
            return vec![([0, 0, width, height], *self)];
        }
        let eye = self.eye_rays();
        if self.projection == Projection::Equirectangular {
            let half = height / 2;
            vec![([0, 0, width, half], eye), ([0, half, width, half], eye)]
        } else {
            let half = width / 2;
            vec![([0, 0, half, height], eye), ([half, 0, half, height], eye)]
        }
    }

    /// The rays of one eye's half of a stereo picture, as a picture of its own: for the
    /// pinhole, half as wide (side by side).
    fn eye_rays(&self) -> Self {
        let aspect = if self.projection == Projection::Perspective {
            0.5 * self.aspect
        } else {
            self.aspect
        };
        Self {
            stereo: None,
            aspect,
            ..*self
        }
    }

    /// The (unnormalised) viewing direction in S through the point `ndc` of normalised device
    /// coordinates (x right, y up, both in [−1, 1]) in the observer's projection, from one eye
    /// at the observer (a stereo pair's rays are [`ViewRays::ray`]'s); `None` where the image
    /// sees nothing (outside a fisheye's circle).
    #[must_use]
    pub fn direction(&self, ndc: DVec2) -> Option<DVec3> {
        match self.projection {
            Projection::Perspective => Some(self.pinhole(ndc)),
            wide => wide.wide_direction(ndc, [self.forward, self.right, self.up]),
        }
    }

    /// Where the direction `direction` (in S) is seen, in normalised device coordinates: the
    /// inverse of [`ViewRays::direction`]; `None` where it is not in the picture (behind the
    /// pinhole, outside a fisheye's field).
    #[must_use]
    pub fn image_point(&self, direction: DVec3) -> Option<DVec2> {
        let basis = [self.forward, self.right, self.up];
        if self.projection != Projection::Perspective {
            return self.projection.wide_image_point(direction, basis);
        }
        let depth = direction.dot(self.forward);
        (depth > 0.0).then(|| {
            DVec2::new(
                direction.dot(self.right) / (depth * self.tan_half * self.aspect),
                direction.dot(self.up) / (depth * self.tan_half),
            )
        })
    }

    /// The pinhole camera's direction through `ndc`.
    fn pinhole(&self, ndc: DVec2) -> DVec3 {
        self.forward
            + (ndc.x * self.tan_half * self.aspect) * self.right
            + (ndc.y * self.tan_half) * self.up
    }
}

/// The lamp: a point light at rest in S (carried by the observer) radiating a Planck spectrum,
/// lighting every surface with the paper's constant strength (no fall-off with distance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Light {
    /// Position in S.
    pub position: DVec3,
    /// Black-body temperature in kelvin.
    pub temperature_k: f64,
    /// Multiplier on all of its light, the ambient term included (1: the paper's lamp; 0: none).
    pub strength: f64,
}

/// Most moving lights a scene may have (the GPU's uniform array holds this many).
pub const MAX_MOVING_LIGHTS: usize = 8;

/// The side in texels of each face of the image-based method's cube map when a scene gives
/// none: the paper's (Table 1, "IB: cube map of 2048² per face").
pub const DEFAULT_CUBE_MAP_SIZE: u32 = 2048;

/// The largest side of an image-based cube map face a scene may ask for (WebGPU's guaranteed
/// texture side is 8192; larger faces are refused by the adapter's own limits).
pub const MAX_CUBE_MAP_SIZE: u32 = 16384;

/// A point light on its own worldline: at rest at the origin of `frame`, radiating a Planck
/// spectrum isotropically in its rest frame. A surface is lit by it as it was at the retarded
/// event, on the past light cone of the surface's event (docs/physics.md, "Moving lights").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovingLight {
    /// The light's rest frame relative to S; the light rests at its origin.
    pub frame: Frame,
    /// Black-body temperature in kelvin, in the light's rest frame.
    pub temperature_k: f64,
    /// Irradiance at unit distance (in the light's rest frame), in units of the lamp's diffuse
    /// light: a surface facing it at distance r receives strength / r² of what the lamp gives.
    pub strength: f64,
}

/// Phong reflection factors of Eq. 18: f_ar = ½(G + 1)(f_amb + f_diff + f_spec).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shading {
    /// The ambient term f_amb.
    pub ambient: f64,
    /// Diffuse weight k_d: f_diff = k_d · max(0, n′·l′).
    pub diffuse: f64,
    /// Specular weight k_s: f_spec = k_s · max(0, r′·v′)^shininess.
    pub specular: f64,
    /// Phong exponent.
    pub shininess: f64,
}

impl Default for Shading {
    fn default() -> Self {
        Self {
            ambient: 0.2,
            diffuse: 0.7,
            specular: 0.25,
            shininess: 32.0,
        }
    }
}

/// One rigid object: its parts, the inertial frame it rests in, and its surface style.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// Name for messages and listings.
    pub name: String,
    /// Meshes with materials, already placed in the rest frame S′.
    pub parts: Vec<Part>,
    /// The rest frame S′ (velocity β and offset **a**).
    pub frame: Frame,
    /// How far the clock of `frame`'s rest coordinates runs ahead of the object's own proper
    /// time (ct″ = ct′ + shift; [`RelativeFrame`]): 0 unless the
    /// observer moves through the world frame.
    pub rest_time_shift: f64,
    /// Draw triangle edges of this width (in S′ units) instead of the texture (Fig. 10 bottom).
    pub wireframe: Option<f64>,
    /// Ultraviolet and infrared reflectances, emission.
    pub optics: SurfaceOptics,
    /// A clock face replacing the texture (drawn unless `wireframe` is set).
    pub clock: Option<Clock>,
    /// How the object moves within `frame`'s rest coordinates (spin, thrust), in S′ time
    /// ct′ ([`Object::proper_time`] of the rest coordinates' time); parts give the body points
    /// at ct′ = 0 (before any thrust).
    pub motion: Motion,
}

impl Object {
    /// The object's proper time ct′ at an event whose time in `frame`'s rest coordinates is
    /// `rest_ct` (what a clock resting on the object shows there; `rest_time_shift`).
    #[must_use]
    pub fn proper_time(&self, rest_ct: f64) -> f64 {
        rest_ct - self.rest_time_shift
    }

    /// Total number of triangles over all parts.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.parts.iter().map(|p| p.mesh.triangles().len()).sum()
    }

    /// How far the body's vertices reach ([`BodyExtent`]): the one measure the moving bodies'
    /// searches of srt-trace and srt-gpu both bound their pieces with.
    #[must_use]
    pub fn body_extent(&self) -> BodyExtent {
        let positions = || self.parts.iter().flat_map(|p| p.mesh.positions().iter());
        let with_triangles = || self.parts.iter().filter(|p| !p.mesh.triangles().is_empty());
        let (lo, hi) = with_triangles()
            .map(|p| p.mesh.bounds())
            .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))
            .unwrap_or((DVec3::ZERO, DVec3::ZERO));
        let middle = (lo + hi) / 2.0;
        let ball_radius = with_triangles()
            .flat_map(|p| p.mesh.positions().iter())
            .map(|p| (*p - middle).length())
            .fold(0.0, f64::max)
            * (1.0 + 1e-12);
        let (reach, axial) = match self.motion {
            Motion::Spin(spin) => (
                positions()
                    .map(|p| (*p - spin.centre()).length())
                    .fold(0.0, f64::max)
                    * (1.0 + 1e-12),
                Some(
                    positions()
                        .map(|p| (*p - spin.centre()).dot(spin.axis()))
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
                            (l.min(x), h.max(x))
                        }),
                ),
            ),
            _ => ((hi - lo).length(), None),
        };
        BodyExtent {
            reach,
            axial,
            bounds: (lo, hi),
            ball: (middle, ball_radius),
        }
    }
}

/// How far a body's vertices at rest reach ([`Object::body_extent`]): what bounds the pieces of
/// a backward ray that the moving bodies' searches meet with its BVH.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyExtent {
    /// A spinning body's largest distance of a vertex from its spin centre (widened by 10⁻¹²
    /// relative, so that rounding cannot put a vertex outside); otherwise the box's diagonal.
    pub reach: f64,
    /// A spinning body's lowest and highest vertex heights along its axis from the centre: a
    /// slab it never leaves. `None` for a body that does not spin.
    pub axial: Option<(f64, f64)>,
    /// The box around the vertices of every part with triangles (a point at the origin for
    /// none).
    pub bounds: (DVec3, DVec3),
    /// The ball around the box's centre holding those vertices (centre, radius; widened as
    /// `reach`): for a round body much smaller than the ball around its box.
    pub ball: (DVec3, f64),
}

/// What of a scene follows the observer's motion, computed from a description by
/// [`crate::SceneDescription::kinematics`]: everything an observer's edit (camera, time,
/// velocity) changes, as long as no object's geometry turns with it.
#[derive(Debug, Clone, PartialEq)]
pub struct Kinematics {
    /// The observer at rest in S.
    pub observer: Observer,
    /// The lamp at rest in S.
    pub light: Light,
    /// The moving lights' rest frames relative to S, in order.
    pub light_frames: Vec<Frame>,
    /// Every object's frame relative to the observer, in order, with the Wigner rotation its
    /// rest-frame geometry is turned by.
    pub frames: Vec<RelativeFrame>,
    /// The velocity of the sky's rest frame W relative to S (`None`: the scene has no sky).
    pub sky_beta: Option<DVec3>,
    /// The transformation from S to the world frame W ([`Scene::world`]).
    pub world: Poincare,
}

/// Everything needed to render one picture.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Name of the scene (built-in name or file stem).
    pub name: String,
    /// The moving objects.
    pub objects: Vec<Object>,
    /// The observer at rest in S.
    pub observer: Observer,
    /// The lamp at rest in S.
    pub light: Light,
    /// The lights moving on their own worldlines (at most [`MAX_MOVING_LIGHTS`]).
    pub lights: Vec<MovingLight>,
    /// Whether objects cast the moving lights' shadows.
    pub shadows: bool,
    /// Phong parameters.
    pub shading: Shading,
    /// Effect mode.
    pub effects: Effects,
    /// Colour table (defaults to the effect mode's).
    pub tone_map: ToneMap,
    /// Display colour (sRGB-encoded, [0, 1]) where no object is hit.
    pub background: DVec3,
    /// Stars at infinity, drawn where no object is hit (none by default).
    pub sky: Sky,
    /// How lit surfaces are coloured.
    pub colour: SurfaceColour,
    /// Multiplier on the light before the tone map (spectral colour; 1 for the paper's).
    pub exposure: f64,
    /// The side in texels of each face of the image-based method's cube map (the GPU's
    /// `image-based` method; [`DEFAULT_CUBE_MAP_SIZE`] unless the scene says otherwise).
    pub cube_map_size: u32,
    /// The transformation from the observer's frame S to the scene's world frame W (the frame
    /// the scene file's times and positions are given in): the identity for an observer at rest
    /// in W ([`MovingObserver::observer_to_world`](srt_physics::MovingObserver)).
    pub world: Poincare,
}

/// A scene's structure beside its objects' parts ([`Scene::structure_beside_parts`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct StructureBesideParts {
    /// Per object: at rest, glowing.
    objects: Vec<(bool, bool)>,
    /// Whether there are moving lights.
    moving_lights: bool,
    /// The sky.
    sky: Sky,
}

impl Scene {
    /// Whether `self` and `other` have the same structure: the same parts (meshes, materials,
    /// textures) per object, the same kind of motion (at rest or not), the same glowing objects,
    /// moving lights in both or in neither, and the same sky. That is what a GPU renderer
    /// uploads; everything else — velocities, times, the observer, lights' places, effects and
    /// colours — is the scene's state, written with each frame. A front end uploads again only
    /// when this is false (an [`crate::Editor`] counts it as its structure version).
    #[must_use]
    pub fn same_structure(&self, other: &Self) -> bool {
        self.objects.len() == other.objects.len()
            && self
                .objects
                .iter()
                .zip(&other.objects)
                .all(|(a, b)| a.parts == b.parts)
            && self.structure_beside_parts() == other.structure_beside_parts()
    }

    /// The structure of the scene beside its parts ([`Scene::same_structure`]): what an editor
    /// that kept every object's parts in place compares, without comparing the meshes.
    pub(crate) fn structure_beside_parts(&self) -> StructureBesideParts {
        StructureBesideParts {
            objects: (self.objects.iter())
                .map(|o| (o.motion.is_rest(), o.optics.emission.is_some()))
                .collect(),
            moving_lights: !self.lights.is_empty(),
            sky: self.sky.clone(),
        }
    }

    /// Total number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.objects.iter().map(Object::triangle_count).sum()
    }

    /// Whether a `width` × `height` picture can hold this scene's view: a stereo pair splits its
    /// picture between the eyes along a side that must be even ([`Stereo::check_size`]); any
    /// size holds one eye's picture.
    ///
    /// # Errors
    /// The reason, naming the scene and the size.
    pub fn check_picture_size(&self, width: u32, height: u32) -> Result<(), String> {
        if self.observer.stereo.is_none() {
            return Ok(());
        }
        Stereo::check_size(self.observer.projection, width, height)
            .map_err(|reason| format!("{}: {reason}", self.name))
    }

    /// A note for a scene drawn in the paper's colour whose surfaces have colours that it turns
    /// grey ([`Part::has_hue`]): what a user's textured model looks like unless told otherwise.
    #[must_use]
    pub fn paper_colour_note(&self) -> Option<String> {
        if self.colour != SurfaceColour::Paper {
            return None;
        }
        let coloured = self
            .objects
            .iter()
            .find(|object| object.parts.iter().any(Part::has_hue))?;
        Some(format!(
            "the paper's colour draws surfaces grey (brightness only), so {}'s colours are lost; \
             spectral colour keeps them and shifts them as light does (--colour spectral, or \
             render.colour = \"spectral\" in the scene file)",
            coloured.name
        ))
    }

    /// How light becomes radiance in this scene's images (srt-color's `radiance` module):
    /// brightness follows luminance with the searchlight effect, the unit is the lamp's light
    /// on a white surface at rest facing it (f_amb + f_diff + f_spec).
    #[must_use]
    pub fn radiance_scale(&self, table: &RadianceTable) -> RadianceScale {
        let shading = self.shading;
        RadianceScale::new(
            table,
            self.effects == Effects::Searchlight,
            self.light.temperature_k,
            shading.ambient + shading.diffuse + shading.specular,
        )
    }

    /// Sets the effect mode and the colour table that goes with it.
    pub fn set_effects(&mut self, effects: Effects) {
        self.effects = effects;
        self.tone_map = effects.default_tone_map();
    }

    /// Moves the scene to `kinematics`, computed from the description it was built from after
    /// an edit of the observer alone: the observer, the light, every object's frame and the
    /// sky's velocity change; meshes, textures and stars stay. The result equals a fresh build
    /// of the edited description when each object's Wigner rotation ([`RelativeFrame::rotation`])
    /// is the one its geometry was built with (always so for an observer at rest in W, and
    /// while the observer's velocity is unchanged); the caller checks that.
    ///
    /// # Panics
    /// If `kinematics` has a different number of objects or lights than the scene.
    pub fn follow(&mut self, kinematics: &Kinematics) {
        assert_eq!(
            kinematics.frames.len(),
            self.objects.len(),
            "kinematics of a description with other objects"
        );
        assert_eq!(
            kinematics.light_frames.len(),
            self.lights.len(),
            "kinematics of a description with other lights"
        );
        self.observer = kinematics.observer;
        self.light = kinematics.light;
        for (light, frame) in self.lights.iter_mut().zip(&kinematics.light_frames) {
            light.frame = *frame;
        }
        self.world = kinematics.world;
        for (object, relative) in self.objects.iter_mut().zip(&kinematics.frames) {
            object.frame = relative.frame;
            object.rest_time_shift = relative.rest_time_shift;
        }
        if let Some(beta) = kinematics.sky_beta {
            self.sky.beta = beta;
        }
    }
}
