//! Request by request onto the description: the dispatcher over the graphics state,
//! `ReadArchive` (and `Procedural "DelayedReadArchive"`, read the same way), and the final assembly (mirror, names, materials, instances, one group
//! `world`, the camera `camera`).

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use glam::{DMat3, DMat4, DVec3};

use super::super::located::{Located, LocatedProblem, Pos, Problem};
use super::area_lights::AreaLights;
use super::atmosphere::{camera_atmosphere, RiFog};
use super::camera::{rows, world_mirror, CameraOptions, DepthOfField};
use super::display;
use super::geometry::{self, Primitive, PRIMITIVES};
use super::lexer;
use super::names::{object_names, Requested};
use super::orientation;
use super::params::{parse_type, Args, Declarations, Param, ParamOwner};
use super::parse::{self, Request};
use super::procedural::{self, ProceduralCall};
use super::requests::{self, SILENT};
use super::retained::{Defining, Motion, Retained, Sample};
use super::shaders::{self, LightShader, DISPLACEMENTS, LIGHTS, SURFACES};
use super::state::{from_rib, rotate, Block, GraphicsState, ShaderCall};
use super::tutorial;
use super::RibScene;
use crate::scene::camera_rotation::{near_similarity, snapped_camera_from_world};
use crate::scene::desc::{
    ApproximationDesc, DisplacementDesc, FaceDesc, FilterDesc, GroupDesc, InstanceDesc, LightDesc,
    LightKindDesc, MaterialDesc, ObjectDesc, OptionsDesc, RenderDesc, SceneDesc, TransformDesc, V3,
};
use crate::scene::suggest::suggestion;

/// Deepest `ReadArchive` nesting.
const MAX_ARCHIVE_DEPTH: usize = 16;

pub(super) struct PendingLight {
    name: String,
    values: shaders::LightValues,
    /// Maps shader space to RIB world space (pre-world lights are completed at WorldBegin).
    to_world: DMat4,
    /// Declared before WorldBegin: `to_world` is still camera space.
    pre_world: bool,
    shadows: bool,
    at: (usize, Pos),
    /// Whether some primitive has it on / off.
    pub used_on: bool,
    pub used_off: bool,
}

/// One object of the description: a mesh with its material, displacement and shading rate.
pub(super) struct PendingObject {
    /// The name it asks for; the name is chosen at assembly ([`super::names`]).
    pub requested: Requested,
    pub prim: Primitive,
    /// Index into the materials.
    pub material: usize,
    pub approximation: Option<(ApproximationDesc, Pos)>,
    pub displacement: Option<(DisplacementDesc, Vec<(String, Pos)>)>,
    /// Inside out: its front is the object-space back.
    pub reverse_orientation: bool,
    pub at: (usize, Pos),
}

/// One instance of the description, placing an object.
pub(super) struct PendingInstance {
    /// Index into the objects.
    pub object: usize,
    /// RIB world ← object space.
    pub world_from_object: DMat4,
    /// A material other than the object's (an `ObjectInstance` with other attributes).
    pub material: Option<usize>,
    /// The name it asks for (`None`: its object's name; one not `given`: its object's name
    /// numbered).
    pub requested: Option<Requested>,
    /// Its caustic flag from AIR's caustic attributes (used when caustics are on).
    pub caustic: u8,
    /// Its `Atmosphere "fog"`.
    pub atmosphere: Option<RiFog>,
    pub at: (usize, Pos),
}

pub(super) struct PendingMaterial {
    pub desc: MaterialDesc,
    pub paths: Vec<(String, Pos)>,
    pub at: (usize, Pos),
    /// Lights switched off by `Illuminate` where the material was used (indices into the
    /// light list): the material's light list is every other light.
    pub lights_off: Vec<usize>,
    /// The area light whose surfaces have the material (its emission).
    pub area_light: Option<usize>,
}

/// The reader's state over one root file and its archives.
pub struct Builder {
    pub(super) files: Vec<PathBuf>,
    pub(super) file: usize,
    pub(super) decls: Declarations,
    pub(super) gs: GraphicsState,
    cam: CameraOptions,
    pub(super) problems: Vec<(usize, Problem)>,
    pub(super) lights: Vec<PendingLight>,
    handles: HashMap<String, usize>,
    /// `AreaLightSource` handles and the primitives they light (an emitting surface is no
    /// light of a light list).
    pub(super) area_lights: AreaLights,
    pub(super) objects: Vec<PendingObject>,
    pub(super) instances: Vec<PendingInstance>,
    pub(super) materials: Vec<PendingMaterial>,
    pub(super) material_keys: HashMap<String, usize>,
    /// Surface calls (file, position) whose parameter problems were reported.
    pub(super) surfaces_reported: HashSet<(usize, Pos)>,
    /// Object definitions (`ObjectBegin`).
    pub(super) retained: Retained,
    /// The motion block being read, and whether the file was told motion blur is not
    /// rendered.
    motion: Option<Motion>,
    motion_warned: bool,
    /// The transformation request before `WorldBegin` that made the current transformation
    /// singular (the camera transformation cannot be one).
    singular_at: Option<(usize, Pos, String)>,
    /// The transformation request before `WorldBegin` after which the current
    /// transformation stopped being a camera's (a rotation, within rounding, and a uniform
    /// scale, mirrored or not): errors about the camera matrix point at it.
    non_rigid_at: Option<(usize, Pos)>,
    coordsys: HashMap<String, DMat4>,
    world: Option<(usize, Pos)>,
    world_ended: bool,
    after_frame_warned: bool,
    depth: usize,
    /// AIR's caustic light (`LightSource "caustic"`): the caustic photon map, where it was
    /// switched on, and the photon and gather counts from AIR's attributes.
    pub(super) caustics: Option<(usize, Pos)>,
    pub(super) photons: Option<(u32, Pos)>,
    pub(super) gather: Option<(u32, Pos)>,
    /// Every AIR caustic attribute read (file, position, class, name): warned about when no
    /// `LightSource "caustic"` switches caustics on.
    pub(super) caustic_attributes: Vec<(usize, Pos, String, String)>,
}

impl Builder {
    /// Reads `path` (contents `bytes`) and everything it includes.
    pub fn run(path: &Path, bytes: &[u8]) -> Result<RibScene, Vec<LocatedProblem>> {
        let mut b = Builder {
            files: vec![path.to_path_buf()],
            file: 0,
            decls: Declarations::default(),
            gs: GraphicsState::default(),
            cam: CameraOptions::default(),
            problems: Vec::new(),
            lights: Vec::new(),
            handles: HashMap::new(),
            area_lights: AreaLights::default(),
            objects: Vec::new(),
            instances: Vec::new(),
            materials: Vec::new(),
            material_keys: HashMap::new(),
            surfaces_reported: HashSet::new(),
            retained: Retained::default(),
            motion: None,
            motion_warned: false,
            singular_at: None,
            non_rigid_at: None,
            coordsys: HashMap::new(),
            world: None,
            world_ended: false,
            after_frame_warned: false,
            depth: 0,
            caustics: None,
            photons: None,
            gather: None,
            caustic_attributes: Vec::new(),
        };
        b.read_text(bytes);
        b.finish_blocks();
        let scene = b.assemble();
        let files = std::mem::take(&mut b.files);
        let mut problems = std::mem::take(&mut b.problems);
        problems.sort_by_key(|(f, p)| (*f, p.pos));
        let problems: Vec<LocatedProblem> = problems
            .into_iter()
            .map(|(f, problem)| LocatedProblem {
                file: files[f].clone(),
                problem,
            })
            .collect();
        if problems.iter().any(|p| !p.problem.warning) {
            // The warnings go with the errors (each says which it is), in position order.
            return Err(problems);
        }
        let warnings = problems;
        let (desc, paths) = scene;
        let paths = paths
            .into_iter()
            .map(|(path, f, pos)| {
                (
                    path,
                    Located {
                        file: files[f].clone(),
                        pos,
                    },
                )
            })
            .collect();
        Ok(RibScene {
            desc,
            paths,
            warnings,
            read_files: files.into_iter().skip(1).collect(),
        })
    }

    fn push(&mut self, p: Problem) {
        self.problems.push((self.file, p));
    }

    fn read_text(&mut self, bytes: &[u8]) {
        let text = super::text::decode(bytes);
        let (tokens, lex_errors) = lexer::tokens(&text);
        let lex_positions: Vec<Pos> = lex_errors.iter().map(|e| e.pos).collect();
        for e in lex_errors {
            self.push(Problem::error(e.pos, e.message));
        }
        let (mut requests, syntax) = parse::requests(&tokens);
        for e in syntax {
            self.push(Problem::error(e.pos, e.message));
        }
        // A request with a lexical error inside is not read either.
        for e in &lex_positions {
            if let Some(r) = requests.iter_mut().rev().find(|r| r.pos <= *e) {
                r.broken = true;
            }
        }
        for r in requests.iter().filter(|r| !r.broken) {
            self.request(r);
        }
    }

    fn finish_blocks(&mut self) {
        if let Some(m) = self.motion.take() {
            self.problems.push((
                0,
                Problem::error(m.pos, "MotionBegin is never closed by MotionEnd"),
            ));
        }
        let open: Vec<(Block, Pos)> = self.gs.open().collect();
        for (b, pos) in open {
            self.problems.push((
                0,
                Problem::error(pos, format!("{} is never closed by {}", b.begin(), b.end())),
            ));
        }
        if self.world.is_none() {
            self.problems.push((
                0,
                Problem::error(
                    Pos::default(),
                    "the file has no WorldBegin: no scene to render",
                )
                .with_help("geometry and lights go between WorldBegin and WorldEnd"),
            ));
        }
    }

    fn request(&mut self, r: &Request) {
        if self.world_ended && !self.after_world(r) {
            return;
        }
        if SILENT.contains(&r.name.as_str()) {
            return;
        }
        let in_motion = !matches!(r.name.as_str(), "MotionBegin" | "MotionEnd");
        if let (Some(m), true) = (&mut self.motion, in_motion) {
            if let Sample::Drop(problem) = m.sample(r) {
                if let Some(p) = problem {
                    self.push(p);
                }
                return;
            }
        }
        if let Some(w) = self.retained.outside_definition(r) {
            self.push(w);
            return;
        }
        let mut problems = Vec::new();
        if let Err(e) = self.dispatch(r, &mut problems) {
            problems.push(e);
        }
        for p in problems {
            self.push(p);
        }
        if !self.in_world() {
            // The request that makes the camera transformation singular, for WorldBegin.
            if invertible(self.gs.attrs.ctm) {
                self.singular_at = None;
            } else if self.singular_at.is_none() {
                self.singular_at = Some((self.file, r.pos, format!("this {}", r.name)));
            }
            if self.world.is_none() {
                if near_similarity(DMat3::from_mat4(self.gs.attrs.ctm)) {
                    self.non_rigid_at = None;
                } else if self.non_rigid_at.is_none() {
                    self.non_rigid_at = Some((self.file, r.pos));
                }
            }
        }
    }

    /// Whether a request after the first `WorldEnd` is read: only the `FrameEnd` that
    /// closes the first frame is. Later frames are not rendered (one warning); they were
    /// checked for syntax only.
    fn after_world(&mut self, r: &Request) -> bool {
        match r.name.as_str() {
            "version" => return true,
            "FrameEnd" if self.gs.inside(Block::Frame) => return true,
            _ => {}
        }
        if !self.after_frame_warned {
            self.after_frame_warned = true;
            self.push(Problem::warning(
                r.pos,
                if r.name == "FrameBegin" {
                    "ignored this frame and every later one: only the first frame is rendered"
                        .to_string()
                } else {
                    format!(
                        "ignored \"{}\" and everything after it: only the first frame is read",
                        r.name
                    )
                },
            ));
        }
        false
    }

    fn in_world(&self) -> bool {
        self.world.is_some()
    }

    fn dispatch(&mut self, r: &Request, problems: &mut Vec<Problem>) -> Result<(), Problem> {
        let name = r.name.as_str();
        let mut a = Args::new(r);
        let option = matches!(
            name,
            "Format"
                | "Projection"
                | "ScreenWindow"
                | "Clipping"
                | "PixelSamples"
                | "PixelFilter"
                | "PixelVariance"
                | "Exposure"
                | "Imager"
                | "Display"
                | "DepthOfField"
        );
        if option && self.in_world() {
            problems.push(Problem::warning(
                r.pos,
                format!(
                    "ignored \"{name}\" inside the world block: options are set before WorldBegin"
                ),
            ));
            return Ok(());
        }
        let placed = PRIMITIVES.contains(&name) && self.retained.defining.is_none()
            || matches!(name, "AreaLightSource" | "ObjectInstance");
        if placed && !self.in_world() {
            return Err(Problem::error(r.pos, format!("{name} before WorldBegin"))
                .with_help("geometry and lights go between WorldBegin and WorldEnd"));
        }
        match name {
            "version" => {
                a.num("version")?;
            }
            "FrameBegin" => {
                if !a.done() {
                    a.num("frame")?;
                }
                self.gs.begin(Block::Frame, r.pos);
            }
            "FrameEnd" => self.end(Block::Frame, r.pos)?,
            "WorldBegin" => {
                if self.in_world() {
                    return Err(Problem::error(r.pos, "WorldBegin inside the world block"));
                }
                self.world = Some((self.file, r.pos));
                let camera = if invertible(self.gs.attrs.ctm) {
                    // A rotation rounded to a few digits (`0.707`) is the rotation it rounds.
                    snapped_camera_from_world(self.gs.attrs.ctm)
                } else {
                    let (file, pos, name) = self.singular_at.take().unwrap_or_else(|| {
                        (
                            self.file,
                            r.pos,
                            "the transformation current at WorldBegin".into(),
                        )
                    });
                    self.problems.push((
                        file,
                        Problem::error(
                            pos,
                            format!("the camera transformation is singular after {name}: it cannot place a camera"),
                        )
                        .with_help("the transformation current at WorldBegin is camera-from-world and must be invertible (no scale by 0)"),
                    ));
                    DMat4::IDENTITY
                };
                self.cam.camera_from_world = Some((camera, r.pos));
                self.coordsys.insert("camera".into(), camera.inverse());
                let m_inv = camera.inverse();
                for l in &mut self.lights {
                    if l.pre_world {
                        l.to_world = m_inv * l.to_world;
                        l.pre_world = false;
                    }
                }
                self.gs.begin(Block::World, r.pos);
                self.gs.attrs.ctm = DMat4::IDENTITY;
                self.coordsys.insert("world".into(), DMat4::IDENTITY);
            }
            "WorldEnd" => {
                self.end(Block::World, r.pos)?;
                self.world_ended = true;
            }
            "AttributeBegin" => self.gs.begin(Block::Attribute, r.pos),
            "AttributeEnd" => self.end(Block::Attribute, r.pos)?,
            "TransformBegin" => self.gs.begin(Block::Transform, r.pos),
            "TransformEnd" => self.end(Block::Transform, r.pos)?,
            "Identity" => self.gs.attrs.ctm = DMat4::IDENTITY,
            "Translate" => {
                let v = vec3(&mut a, ["dx", "dy", "dz"])?;
                self.gs.concat(DMat4::from_translation(v));
            }
            "Scale" => {
                let v = vec3(&mut a, ["sx", "sy", "sz"])?;
                self.gs.concat(DMat4::from_scale(v));
            }
            "Rotate" => {
                let (angle, _) = a.num("angle")?;
                let axis = vec3(&mut a, ["dx", "dy", "dz"])?;
                let m = rotate(angle, axis)
                    .ok_or_else(|| Problem::error(r.pos, "Rotate about a zero axis"))?;
                self.gs.concat(m);
            }
            "ConcatTransform" | "Transform" => {
                let m = a.array("transform")?;
                let v = m.value.nums().unwrap_or(&[]);
                if v.len() != 16 {
                    return Err(Problem::error(
                        m.pos,
                        format!("{name} takes 16 numbers, found {}", v.len()),
                    ));
                }
                let t = from_rib(v);
                if name == "Transform" {
                    self.gs.attrs.ctm = t;
                } else {
                    self.gs.concat(t);
                }
            }
            "CoordinateSystem" => {
                let (n, _) = a.string("name")?;
                self.coordsys.insert(n, self.gs.attrs.ctm);
            }
            "CoordSysTransform" => {
                let (n, pos) = a.string("name")?;
                match self.coordsys.get(&n) {
                    Some(m) => self.gs.attrs.ctm = *m,
                    None => {
                        let names: Vec<&str> = self.coordsys.keys().map(String::as_str).collect();
                        let mut e =
                            Problem::error(pos, format!("unknown coordinate system \"{n}\""));
                        e.help = suggestion(&n, &names, "CoordinateSystem names");
                        return Err(e);
                    }
                }
            }
            "Color" | "Opacity" => {
                let mut c = [0.0; 3];
                let mut at = [Pos::default(); 3];
                for (k, channel) in ["red", "green", "blue"].iter().enumerate() {
                    (c[k], at[k]) = a.num(channel)?;
                }
                shaders::check_colour(name, name == "Opacity", c, at)?;
                let c = (c[0], c[1], c[2]);
                if name == "Color" {
                    self.gs.attrs.color = c;
                } else {
                    self.gs.attrs.opacity = c;
                }
            }
            "Sides" => {
                let (n, pos) = a.count("sides", 1)?;
                if n > 2 {
                    return Err(Problem::error(
                        pos,
                        format!("Sides must be 1 or 2, found {n}"),
                    ));
                }
                self.gs.attrs.sides = n as u32;
            }
            "Orientation" => {
                let (token, pos) = a.string("orientation")?;
                let camera_from_current = match self.cam.camera_from_world {
                    Some((camera_from_world, _)) => camera_from_world * self.gs.attrs.ctm,
                    None => self.gs.attrs.ctm,
                };
                let rh = orientation::right_handed(camera_from_current);
                self.gs.attrs.inside_out = orientation::inside_out(&token, rh, pos)?;
            }
            "ReverseOrientation" => self.gs.attrs.inside_out = !self.gs.attrs.inside_out,
            "ShadingRate" => {
                let (v, pos) = a.num("size")?;
                if v.is_nan() || v <= 0.0 {
                    return Err(Problem::error(
                        pos,
                        format!("ShadingRate must be > 0, found {v}"),
                    ));
                }
                self.gs.attrs.shading_rate = Some((v, pos));
            }
            "Declare" => {
                let (n, _) = a.string("name")?;
                let (ty, pos) = a.string("declaration")?;
                let d = parse_type(&ty).map_err(|m| Problem::error(pos, m))?;
                self.decls.declare(&n, d);
            }
            "Basis" => {
                let dir = |a: &mut Args<'_>,
                           d: &str|
                 -> Result<super::state::BasisState, Problem> {
                    let (b, pos) = a.string(&format!("{d}basis"))?;
                    let (step, _) = a.count(&format!("{d}step"), 1)?;
                    let basis = geometry::basis(&b, step).map_err(|m| Problem::error(pos, m))?;
                    Ok(super::state::BasisState {
                        basis,
                        step,
                        pos: Some(pos),
                    })
                };
                let u = dir(&mut a, "u")?;
                let v = dir(&mut a, "v")?;
                self.gs.attrs.basis = (u, v);
            }
            "ReadArchive" => {
                let (f, pos) = a.string("filename")?;
                self.archive(&f, pos, name);
            }
            "Procedural" | "Procedural2" => match procedural::read(r, &mut a)? {
                ProceduralCall::Archive { file, pos } => {
                    if !self.in_world() && self.retained.defining.is_none() {
                        return Err(Problem::error(
                            r.pos,
                            "Procedural \"DelayedReadArchive\" before WorldBegin",
                        )
                        .with_help("geometry and lights go between WorldBegin and WorldEnd"));
                    }
                    self.archive(&file, pos, "DelayedReadArchive");
                }
                ProceduralCall::Missing(w) => {
                    // The plug-in's arguments are not read.
                    problems.push(w);
                    return Ok(());
                }
            },
            "Surface" | "Displacement" | "AreaLightSource" | "LightSource" => {
                return self.shader(name, r, a, problems);
            }
            "Illuminate" => {
                let handle = self.handle(&mut a, "light handle")?;
                let (on, on_pos) = a.num("onoff")?;
                if let Some(id) = self.area_lights.id(&handle.0) {
                    let off = &mut self.gs.attrs.area_lights_off;
                    self.area_lights
                        .illuminate(id, on != 0.0, (self.file, on_pos), off);
                } else {
                    let Some(&i) = self.handles.get(&handle.0) else {
                        return Err(Problem::error(
                            handle.1,
                            format!("unknown light handle {}", handle.0),
                        ));
                    };
                    self.gs.attrs.lights_off.retain(|&l| l != i);
                    if on == 0.0 {
                        self.gs.attrs.lights_off.push(i);
                    }
                }
            }
            "Attribute" => return self.attribute(a, problems),
            "Format" => {
                let (w, wp) = a.count("xresolution", 1)?;
                let (h, _) = a.count("yresolution", 1)?;
                let (pa, ppos) = a.num("pixelaspectratio")?;
                let pa = if pa > 0.0 {
                    pa
                } else {
                    problems.push(Problem::warning(
                        ppos,
                        format!("pixel aspect ratio {pa} is not positive: using 1 (square pixels, the display's default)"),
                    ));
                    1.0
                };
                self.cam.format = Some(((w as u32, h as u32, pa), wp));
            }
            "Projection" => {
                let (kind, pos) = a.string("name")?;
                self.cam.projection = Some(r.pos);
                let params = a.params(&self.decls, problems);
                if kind != "perspective" {
                    problems.push(
                        Problem::error(
                            pos,
                            format!(
                                "Projection \"{kind}\" is not supported: stagelight's camera \
                                 makes perspective projections only"
                            ),
                        )
                        .with_help("use Projection \"perspective\" \"fov\" [degrees]"),
                    );
                }
                for p in params {
                    if p.name == "fov" && p.nums().len() == 1 {
                        let f = p.num();
                        if !(f > 0.0 && f < 180.0) {
                            problems.push(Problem::error(
                                p.pos(),
                                format!("fov must be in (0, 180) degrees, found {f}"),
                            ));
                        } else {
                            self.cam.fov = Some((f, p.pos()));
                        }
                    } else {
                        problems.push(ignored_param(&p, "Projection"));
                    }
                }
                return Ok(());
            }
            "ScreenWindow" => {
                let mut s = [0.0; 4];
                for (i, n) in ["left", "right", "bottom", "top"].iter().enumerate() {
                    s[i] = a.num(n)?.0;
                }
                if !(s.iter().all(|x| x.is_finite()) && s[1] > s[0] && s[3] > s[2]) {
                    return Err(Problem::error(
                        r.pos,
                        format!(
                            "ScreenWindow needs left < right and bottom < top, found {} {} {} {}",
                            s[0], s[1], s[2], s[3]
                        ),
                    ));
                }
                self.cam.screen = Some((s, r.pos));
            }
            "DepthOfField" => self.cam.depth_of_field = depth_of_field(r, &mut a)?,
            "Atmosphere" => return self.atmosphere(r, a, problems),
            "Clipping" => {
                let (near, _) = a.num("near")?;
                let (far, _) = a.num("far")?;
                if near > 1e-5 || far.is_finite() && far < 1e30 {
                    problems.push(Problem::warning(
                        r.pos,
                        format!("ignored Clipping {near} {far}: the camera has no clipping planes"),
                    ));
                }
            }
            "PixelSamples" => {
                let (x, xpos) = a.num("xsamples")?;
                let (y, ypos) = a.num("ysamples")?;
                let low = [(x, xpos), (y, ypos)].into_iter().find(|(v, _)| *v < 1.0);
                let (x, y) = (x.max(1.0).ceil(), y.max(1.0).ceil());
                if let Some((v, pos)) = low {
                    problems.push(Problem::warning(
                        pos,
                        format!("PixelSamples {v} is below 1, taken as 1: rendering {x} × {y} samples per pixel"),
                    ));
                }
                let n = (x * y).min(1e6) as u64;
                self.cam.samples = Some((n, r.pos));
            }
            "PixelVariance" => {
                problems.push(Problem::warning(
                    r.pos,
                    "ignored PixelVariance: sampling is fixed per pixel",
                ));
            }
            "PixelFilter" => {
                let (f, pos) = a.string("filter")?;
                let (xw, xw_pos) = a.num("xwidth")?;
                let (yw, _) = a.num("ywidth")?;
                // Checked here in RIB's terms (a width, at its token): the description's
                // Gaussian has half of it as radius and a quarter as sigma.
                let widest = 2.0 * crate::settings::MAX_FILTER_RADIUS;
                if !(xw > 0.0 && xw <= widest) && f != "box" {
                    return Err(Problem::error(
                        xw_pos,
                        format!("PixelFilter width must be above 0 and at most {widest} pixels, found {xw}"),
                    )
                    .with_help(format!(
                        "a width of 2 to 4 pixels is usual (`PixelFilter \"{f}\" 2 2`)"
                    )));
                }
                if xw != yw {
                    problems.push(Problem::warning(
                        pos,
                        format!("PixelFilter widths differ: using {xw} in both directions"),
                    ));
                }
                let filter = match f.as_str() {
                    "gaussian" => FilterDesc::Gaussian {
                        sigma: xw / 4.0,
                        radius: xw / 2.0,
                    },
                    "box" => {
                        if xw != 1.0 {
                            problems.push(Problem::warning(
                                pos,
                                format!(
                                    "PixelFilter \"box\" {xw}: the box filter covers one pixel"
                                ),
                            ));
                        }
                        FilterDesc::Box
                    }
                    other => {
                        problems.push(Problem::warning(pos, format!("PixelFilter \"{other}\" is not supported: using \"gaussian\" {xw} {yw}")));
                        FilterDesc::Gaussian {
                            sigma: xw / 4.0,
                            radius: xw / 2.0,
                        }
                    }
                };
                self.cam.filter = Some((filter, r.pos));
            }
            "Exposure" => {
                let (gain, _) = a.num("gain")?;
                let (gamma, _) = a.num("gamma")?;
                self.cam.exposure = Some(((gain, gamma), r.pos));
            }
            "Imager" => {
                let (n, pos) = a.string("name")?;
                let background = ParamOwner {
                    what: "imager \"background\"".into(),
                    names: &["background"],
                };
                let named = tutorial::parameter_names("Imager", &n);
                let tutorial_owner = named.as_ref().map(|(what, names)| ParamOwner {
                    what: format!("{what} \"{n}\""),
                    names,
                });
                let owner = if n == "background" {
                    Some(&background)
                } else {
                    tutorial_owner.as_ref()
                };
                let params = a.params_of(&self.decls, owner, problems);
                if tutorial::IMAGERS.contains(&n.as_str()) {
                    // The tutorial's imager (seed 001 §3.2.3) paints a pattern of raster
                    // position over every pixel; it replaces any imager called before.
                    let call = ShaderCall {
                        name: n.clone(),
                        pos: r.pos,
                        file: self.file,
                        params,
                    };
                    self.cam.pattern = Some((tutorial::imager(&call, problems), pos));
                    self.cam.background = None;
                    return Ok(());
                }
                if n != "background" {
                    let mut w = Problem::warning(
                        pos,
                        format!("ignored imager shader \"{n}\": not one of ours"),
                    );
                    let known = [&["background"][..], tutorial::IMAGERS].concat();
                    w.help = suggestion(&n, &known, "shaders");
                    problems.push(w);
                    return Ok(());
                }
                self.cam.pattern = None;
                for p in params {
                    if p.name == "background" && p.nums().len() == 3 {
                        self.cam.background = Some((p.triple(), p.pos()));
                    } else {
                        let mut e = Problem::error(
                            p.name_pos,
                            format!("unknown parameter \"{}\" of imager \"background\"", p.name),
                        );
                        e.help = suggestion(&p.name, &["background"], "parameters");
                        problems.push(e);
                    }
                }
                return Ok(());
            }
            "Display" => {
                let d = display::read(a, &self.decls, problems)?;
                if !d.append {
                    self.cam.displays.clear();
                }
                self.cam.displays.push(d.display);
                return Ok(());
            }
            "ObjectBegin" => {
                let (handle, _) = self.handle(&mut a, "object handle")?;
                if let Some(d) = &self.retained.defining {
                    return Err(Problem::error(
                        r.pos,
                        format!(
                            "ObjectBegin inside the object definition opened at {}:{}",
                            d.pos.line, d.pos.column
                        ),
                    )
                    .with_help("close it with ObjectEnd first"));
                }
                self.gs.begin(Block::Object, r.pos);
                // The object's own space: its transformations apply where it is instanced.
                self.gs.attrs.ctm = DMat4::IDENTITY;
                self.retained.defining = Some(Defining {
                    handle,
                    pos: r.pos,
                    prims: Vec::new(),
                });
            }
            "ObjectEnd" => {
                let ended = self.end(Block::Object, r.pos);
                if !self.gs.inside(Block::Object) {
                    if let Some(d) = self.retained.defining.take() {
                        self.retained.defined.insert(d.handle, d.prims);
                    }
                }
                ended?;
            }
            "ObjectInstance" => {
                let (handle, hpos) = self.handle(&mut a, "object handle")?;
                let Some(mut prims) = self.retained.defined.remove(&handle) else {
                    let names: Vec<&str> =
                        self.retained.defined.keys().map(String::as_str).collect();
                    let shown = if handle.parse::<f64>().is_ok() {
                        handle.clone()
                    } else {
                        format!("\"{handle}\"")
                    };
                    let mut e = Problem::error(hpos, format!("unknown object handle {shown}"));
                    e.help = suggestion(&handle, &names, "objects (ObjectBegin)");
                    return Err(e);
                };
                self.instance(&mut prims, r, problems);
                self.retained.defined.insert(handle, prims);
            }
            "MotionBegin" => {
                let mut n = 0;
                while !a.done() {
                    a.num("times")?;
                    n += 1;
                }
                if let Some(m) = &self.motion {
                    return Err(Problem::error(
                        r.pos,
                        format!(
                            "MotionBegin inside the motion block opened at {}:{}",
                            m.pos.line, m.pos.column
                        ),
                    ));
                }
                if !self.motion_warned {
                    self.motion_warned = true;
                    problems.push(Problem::warning(
                        r.pos,
                        "motion blur is not rendered: each motion block uses its first time \
                         sample",
                    ));
                }
                self.motion = Some(Motion {
                    pos: r.pos,
                    times: n,
                    first: None,
                    count: 0,
                    mixed: false,
                });
            }
            "MotionEnd" => {
                let m = self
                    .motion
                    .take()
                    .ok_or_else(|| Problem::error(r.pos, "MotionEnd without MotionBegin"))?;
                if let Some(p) = m.end(r.pos) {
                    problems.push(p);
                }
            }
            _ if PRIMITIVES.contains(&name) => self.primitive(r, problems),
            _ => {
                if let Some(w) = requests::ignored(name, r.pos) {
                    problems.push(w);
                    return Ok(());
                }
                return Err(requests::unknown(name, r.pos));
            }
        }
        let checked = !PRIMITIVES.contains(&name);
        if checked && !a.done() {
            let extra = r.args.last().map_or(r.pos, |x| x.pos);
            problems.push(Problem::error(
                extra,
                format!("too many arguments for {name}"),
            ));
        }
        Ok(())
    }

    /// Closes `block`. The light list is an attribute: a light declared inside an ended
    /// block (other than a transform block) is off from here on, until `Illuminate`.
    fn end(&mut self, block: Block, pos: Pos) -> Result<(), Problem> {
        let ended = self.gs.end(block).map_err(|m| Problem::error(pos, m));
        let attrs = &mut self.gs.attrs;
        attrs
            .lights_off
            .extend(attrs.lights_known..self.lights.len());
        attrs.lights_known = self.lights.len();
        ended
    }

    /// A light or object handle: a number or a string.
    fn handle(&self, a: &mut Args<'_>, what: &str) -> Result<(String, Pos), Problem> {
        if a.peek_is_string() {
            a.string(what)
        } else {
            let (v, p) = a.num(what)?;
            Ok((format!("{v}"), p))
        }
    }

    /// Reads the archive file `name` (relative to the file being read) here, for `request`
    /// (`ReadArchive` or `DelayedReadArchive`), at the file name's position `pos`.
    fn archive(&mut self, name: &str, pos: Pos, request: &str) {
        if self.depth >= MAX_ARCHIVE_DEPTH {
            self.push(Problem::error(
                pos,
                format!("{request} nests deeper than {MAX_ARCHIVE_DEPTH} files"),
            ));
            return;
        }
        let dir = self.files[self.file]
            .parent()
            .map(Path::to_path_buf)
            .unwrap_or_default();
        let path = dir.join(name);
        let read =
            crate::limits::read_file(&path, crate::limits::MAX_SCENE_FILE_BYTES, "scene file");
        let bytes = match read {
            Ok(b) => b,
            Err(e) => {
                self.push(Problem::error(
                    pos,
                    format!(
                        "cannot read archive \"{}\": {}",
                        path.display(),
                        crate::scene::message::io_reason(&e)
                    ),
                ));
                return;
            }
        };
        let saved = self.file;
        self.files.push(path);
        self.file = self.files.len() - 1;
        self.depth += 1;
        self.read_text(&bytes);
        self.depth -= 1;
        self.file = saved;
    }

    fn shader(
        &mut self,
        kind: &str,
        r: &Request,
        mut a: Args<'_>,
        problems: &mut Vec<Problem>,
    ) -> Result<(), Problem> {
        let (name, npos) = a.string("shader name")?;
        let handle = if matches!(kind, "LightSource" | "AreaLightSource") {
            Some(self.handle(&mut a, "light handle")?)
        } else {
            None
        };
        // A shader of ours names its parameters, so an undeclared one is a parameter it
        // does not take.
        let known = shaders::parameter_names(kind, &name);
        let owner = known.as_ref().map(|(what, names)| ParamOwner {
            what: what.clone(),
            names,
        });
        let params = a.params_of(&self.decls, owner.as_ref(), problems);
        let call = ShaderCall {
            name: name.clone(),
            pos: r.pos,
            file: self.file,
            params,
        };
        if kind == "LightSource" && name == "caustic" {
            for p in &call.params {
                problems.push(ignored_param(p, "LightSource \"caustic\""));
            }
            self.caustics = Some((self.file, r.pos));
            return Ok(());
        }
        // The standard shaders and the tutorial's (`super::tutorial`), known by name.
        let known: Vec<&str> = match kind {
            "Surface" => [SURFACES, tutorial::SURFACES].concat(),
            "Displacement" => [DISPLACEMENTS, tutorial::DISPLACEMENTS].concat(),
            "AreaLightSource" => vec!["arealight"],
            _ => [LIGHTS, tutorial::LIGHTS].concat(),
        };
        if !known.contains(&name.as_str()) {
            let what = kind.to_lowercase();
            let mut w = Problem::warning(
                npos,
                match kind {
                    "Surface" => {
                        format!("unknown surface shader \"{name}\": using \"defaultsurface\"")
                    }
                    _ => format!("ignored {what} shader \"{name}\": not one of ours"),
                },
            );
            w.help = suggestion(&name, &known, "shaders");
            problems.push(w);
            if kind == "Surface" {
                self.gs.attrs.surface = None;
            }
            return Ok(());
        }
        match kind {
            "Surface" => {
                // Its problems are reported here, whether or not a primitive uses it.
                shaders::check_coefficients(&call, problems);
                self.gs.attrs.surface = Some(call);
            }
            "Displacement" => {
                // Its problems are reported here, whether or not a primitive uses it.
                shaders::displacement(&call, problems);
                self.gs.attrs.displacement = Some(call);
            }
            "AreaLightSource" => {
                for p in &call.params {
                    if !matches!(p.name.as_str(), "intensity" | "lightcolor") {
                        let mut e = Problem::error(
                            p.name_pos,
                            format!("unknown parameter \"{}\" of light \"arealight\"", p.name),
                        );
                        e.help = suggestion(&p.name, &["intensity", "lightcolor"], "parameters");
                        problems.push(e);
                    }
                }
                shaders::check_coefficients(&call, problems);
                self.gs.attrs.area_light = Some(call);
                let h = handle.map_or_else(String::new, |(h, _)| h);
                self.handles.remove(&h);
                self.gs.attrs.area_light_id = Some(self.area_lights.define(&h));
            }
            _ => {
                let values = shaders::light(&call, problems);
                let n = self.lights.len();
                let lname = format!("{name}_{}", n + 1);
                if let Some((h, _)) = handle {
                    self.area_lights.forget(&h);
                    self.handles.insert(h, n);
                }
                self.lights.push(PendingLight {
                    name: lname,
                    values,
                    to_world: self.gs.attrs.ctm,
                    pre_world: !self.in_world(),
                    shadows: self.gs.attrs.light_shadows,
                    at: (self.file, r.pos),
                    used_on: false,
                    used_off: false,
                });
                self.gs.attrs.lights_known = self.lights.len();
            }
        }
        Ok(())
    }

    fn attribute(&mut self, mut a: Args<'_>, problems: &mut Vec<Problem>) -> Result<(), Problem> {
        let (class, cpos) = a.string("name")?;
        let params = a.params_lenient(&self.decls, problems);
        for p in params {
            if self.air_caustic_attribute(&class, &p, problems) {
                continue;
            }
            match (class.as_str(), p.name.as_str()) {
                ("displacementbound", "sphere") if p.nums().len() == 1 => {
                    self.gs.attrs.displacement_bound = Some((p.num(), p.pos()));
                }
                ("displacementbound", "coordinatesystem")
                    if matches!(p.str(), "object" | "shader" | "current") => {}
                ("render", "truedisplacement") if p.nums().len() == 1 => {
                    self.gs.attrs.true_displacement = p.num() != 0.0;
                }
                ("identifier", "name") if p.decl.ty == super::params::Ty::Str => {
                    self.gs.attrs.name = Some(p.str().to_string());
                }
                ("light", "shadows") if p.decl.ty == super::params::Ty::Str => {
                    self.gs.attrs.light_shadows = p.str() == "on";
                }
                _ => problems.push(Problem::warning(
                    p.name_pos,
                    format!("ignored Attribute \"{class}\" \"{}\"", p.name),
                )),
            }
        }
        let _ = cpos;
        Ok(())
    }

    /// The description and the paths of its values.
    fn assemble(&mut self) -> (SceneDesc, Vec<(String, usize, Pos)>) {
        let mut paths: Vec<(String, usize, Pos)> = Vec::new();
        let (wfile, wpos) = self.world.unwrap_or((0, Pos::default()));
        let m = self.cam.camera_from_world.map_or(DMat4::IDENTITY, |c| c.0);
        let g = world_mirror(m);
        let (mut camera, cpaths) = self.cam.camera(wpos);
        for (p, pos) in cpaths {
            // The matrix is where the request that made it no camera's is.
            let (file, pos) = match self.non_rigid_at {
                Some(at) if p == ".placement.Matrix[0]" => at,
                _ => (wfile, pos),
            };
            paths.push((format!("cameras[0]{p}"), file, pos));
        }
        let scale = self.cam.world_per_camera_unit();
        if let Some((fade, fog)) = camera_atmosphere(&self.instances, scale, &mut self.problems) {
            let (file, pos) = fog.at;
            paths.push(("cameras[0].atmosphere".into(), file, pos));
            let (_, dpos) = fog.values.distance;
            let (_, bpos) = fog.values.background;
            paths.push((
                "cameras[0].atmosphere.Fade.max".into(),
                file,
                dpos.unwrap_or(pos),
            ));
            paths.push((
                "cameras[0].atmosphere.Fade.color".into(),
                file,
                bpos.unwrap_or(pos),
            ));
            camera.atmosphere = Some(fade);
        }
        let mut desc = SceneDesc {
            options: Some(OptionsDesc {
                samples: self.cam.samples(),
                filter: self.cam.filter(),
                // `Sides 1` (one-sided materials): only the outside is visible, the inside
                // is left out of every ray (RISpec 3.2, "Orientation and Sides").
                face: FaceDesc::Cull,
                ..OptionsDesc::default()
            }),
            cameras: vec![camera],
            ..SceneDesc::default()
        };
        paths.push(("options".into(), wfile, wpos));
        if let Some((_, p)) = self.cam.samples {
            paths.push(("options.samples".into(), wfile, p));
        }
        if let Some((_, p)) = self.cam.filter {
            paths.push(("options.filter".into(), wfile, p));
        }
        self.caustic_map(&mut desc, &mut paths);
        for l in &self.lights {
            if !l.used_on && l.used_off {
                self.problems.push((
                    l.at.0,
                    Problem::warning(
                        l.at.1,
                        format!(
                            "light \"{}\" is switched off for every primitive: left out",
                            l.name
                        ),
                    ),
                ));
                continue;
            }
            let t = g * l.to_world;
            let pt = |v: V3| {
                let p = t.transform_point3(DVec3::new(v.0, v.1, v.2));
                (p.x, p.y, p.z)
            };
            // RenderMan's point and spot lights fall off as 1/d²; the tutorial's `myLight`
            // ramps from `near` to `far` instead.
            let mut falloff = (true, None);
            let kind = match l.values.shader {
                LightShader::Ambient => LightKindDesc::Ambient,
                LightShader::Point { from } => LightKindDesc::Point { position: pt(from) },
                LightShader::Ramp { from, near, far } => {
                    falloff = (false, Some((near, far)));
                    LightKindDesc::Point { position: pt(from) }
                }
                LightShader::Distant { from, to } => {
                    let (a, b) = (pt(from), pt(to));
                    LightKindDesc::Directional {
                        direction: (b.0 - a.0, b.1 - a.1, b.2 - a.2),
                    }
                }
                LightShader::Spot {
                    from,
                    to,
                    cone,
                    delta,
                    beam,
                } => {
                    let cone_angle = cone.to_degrees();
                    LightKindDesc::Spot {
                        position: pt(from),
                        target: pt(to),
                        cone_angle,
                        penumbra: delta.to_degrees().min(cone_angle).max(0.0),
                        beam_distribution: beam,
                    }
                }
            };
            let i = desc.lights.len();
            paths.push((format!("lights[{i}]"), l.at.0, l.at.1));
            paths.push((format!("lights[{i}].kind"), l.at.0, l.at.1));
            for (p, pos) in &l.values.paths {
                paths.push((format!("lights[{i}]{p}"), l.at.0, *pos));
            }
            desc.lights.push(LightDesc {
                name: l.name.clone(),
                kind,
                color: l.values.color,
                intensity: l.values.intensity,
                shadows: l.shadows,
                shadow_factor: 0.0,
                samples: None,
                visible: false,
                attenuation: falloff.1,
                energy: None,
                caustic_photons: None,
                globillum_photons: None,
                inverse_square: falloff.0,
            });
        }
        let caustics_on = self.caustics.is_some();
        // Area lights off for every primitive they could light emit nothing.
        let (dark, warnings) = self.area_lights.finish();
        self.problems.extend(warnings);
        for (i, m) in self.materials.iter().enumerate() {
            paths.push((format!("materials[{i}]"), m.at.0, m.at.1));
            paths.push((format!("materials[{i}].shader"), m.at.0, m.at.1));
            for (p, pos) in &m.paths {
                paths.push((format!("materials[{i}]{p}"), m.at.0, *pos));
            }
            let mut material = m.desc.clone();
            if m.area_light.is_some_and(|a| dark.contains(&a)) {
                material.emission = (0.0, 0.0, 0.0);
            }
            if !caustics_on {
                // AIR's caustic attributes do nothing without its caustic light (warned).
                material.photon = None;
            }
            if !m.lights_off.is_empty() {
                // `Illuminate handle 0`: lit by every light written but those.
                let names = self
                    .lights
                    .iter()
                    .enumerate()
                    .filter(|(j, l)| !m.lights_off.contains(j) && (l.used_on || !l.used_off));
                material.lights = Some(names.map(|(_, l)| l.name.clone()).collect());
            }
            desc.materials.push(material);
        }
        let requested: Vec<Requested> = self.objects.iter().map(|o| o.requested.clone()).collect();
        let names = object_names(&requested);
        for (i, (o, name)) in self.objects.drain(..).zip(&names).enumerate() {
            let (f, pos) = o.at;
            paths.push((format!("objects[{i}]"), f, pos));
            paths.push((format!("objects[{i}].mesh"), f, pos));
            for (p, vpos) in &o.prim.paths {
                paths.push((format!("objects[{i}].mesh{p}"), f, *vpos));
            }
            if let Some((_, p)) = &o.approximation {
                paths.push((format!("objects[{i}].approximation"), f, *p));
            }
            if let Some((_, dp)) = &o.displacement {
                for (p, vpos) in dp {
                    paths.push((format!("objects[{i}].displacement{p}"), f, *vpos));
                }
            }
            desc.objects.push(ObjectDesc {
                name: name.clone(),
                mesh: o.prim.mesh,
                material: Some(desc.materials[o.material].name.clone()),
                approximation: o.approximation.map(|a| a.0),
                displacement: o.displacement.map(|d| d.0),
                derivatives: false,
                reverse_orientation: o.reverse_orientation,
                caustic: None,
                globillum: None,
                visible: None,
                shadow: None,
                trace: None,
                label: None,
            });
        }
        // An instance of a primitive takes its object's name; an `ObjectInstance` its
        // identifier, else its object's name numbered.
        let requested: Vec<Requested> = self
            .instances
            .iter()
            .map(|i| match &i.requested {
                None => Requested {
                    base: names[i.object].clone(),
                    given: true,
                },
                Some(r) if r.given => r.clone(),
                Some(_) => Requested {
                    base: names[i.object].clone(),
                    given: false,
                },
            })
            .collect();
        let instance_names = object_names(&requested);
        let mut members = Vec::new();
        for (i, (inst, name)) in self.instances.drain(..).zip(instance_names).enumerate() {
            let (f, pos) = inst.at;
            paths.push((format!("instances[{i}]"), f, pos));
            paths.push((format!("instances[{i}].transform[0]"), f, pos));
            let mut instance = InstanceDesc::plain(
                &name,
                &names[inst.object],
                vec![TransformDesc::Matrix(rows(g * inst.world_from_object))],
            );
            if let Some(m) = inst.material {
                paths.push((format!("instances[{i}].material"), f, pos));
                instance.material = Some(desc.materials[m].name.clone());
            }
            if caustics_on {
                // AIR: only the caustic attributes make a primitive cast or receive.
                paths.push((format!("instances[{i}].caustic"), f, pos));
                instance.caustic = Some(inst.caustic);
            }
            desc.instances.push(instance);
            members.push(name);
        }
        paths.push(("groups[0]".into(), wfile, wpos));
        paths.push(("render".into(), wfile, wpos));
        desc.groups.push(GroupDesc {
            name: "world".into(),
            members,
        });
        desc.render = Some(RenderDesc {
            root: "world".into(),
            camera: "camera".into(),
        });
        (desc, paths)
    }
}

/// Whether `m` can be inverted (its determinant finite and not 0).
fn invertible(m: DMat4) -> bool {
    let det = m.determinant();
    det.is_finite() && det != 0.0
}

fn vec3(a: &mut Args<'_>, names: [&str; 3]) -> Result<DVec3, Problem> {
    let x = a.num(names[0])?.0;
    let y = a.num(names[1])?.0;
    let z = a.num(names[2])?.0;
    Ok(DVec3::new(x, y, z))
}

/// `DepthOfField fstop focallength focaldistance` (`None`: no arguments or an infinite
/// `fstop`, RISpec 3.2's way to turn depth of field off — `RI_INFINITY` is 1e38).
fn depth_of_field(r: &Request, a: &mut Args<'_>) -> Result<Option<DepthOfField>, Problem> {
    if a.done() {
        return Ok(None);
    }
    let (fstop, _) = a.num("fstop")?;
    let (focal, _) = a.num("focallength")?;
    let (focus, focus_pos) = a.num("focaldistance")?;
    if fstop >= 1e30 {
        return Ok(None);
    }
    if !(fstop > 0.0 && focal > 0.0 && focal.is_finite() && focus > 0.0 && focus.is_finite()) {
        return Err(Problem::error(
            r.pos,
            format!(
                "DepthOfField needs fstop > 0, focallength > 0 and focaldistance > 0, found \
                 {fstop} {focal} {focus}"
            ),
        )
        .with_help("`DepthOfField` without arguments turns depth of field off"));
    }
    Ok(Some(DepthOfField {
        radius: focal / (2.0 * fstop),
        focus,
        pos: r.pos,
        focus_pos,
    }))
}

fn ignored_param(p: &Param, request: &str) -> Problem {
    Problem::warning(
        p.name_pos,
        format!("ignored parameter \"{}\" of {request}", p.name),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::desc::{MeshDesc, ShaderDesc};

    fn read(text: &str) -> RibScene {
        Builder::run(Path::new("t.rib"), text.as_bytes()).unwrap_or_else(|e| {
            panic!(
                "{}",
                e.iter()
                    .map(|e| e.to_string())
                    .collect::<Vec<_>>()
                    .join("\n")
            )
        })
    }

    fn matrix(desc: &SceneDesc, i: usize) -> [[f64; 4]; 4] {
        match &desc.instances[i].transform[..] {
            [TransformDesc::Matrix(m)] => *m,
            other => panic!("{other:?}"),
        }
    }

    fn close(a: [[f64; 4]; 4], b: [[f64; 4]; 4]) {
        for r in 0..4 {
            for c in 0..4 {
                assert!((a[r][c] - b[r][c]).abs() < 1e-12, "{a:?}\n!=\n{b:?}");
            }
        }
    }

    #[test]
    fn torus_of_shadertest_with_its_transform() {
        let s = read(
            "WorldBegin\nAttributeBegin\nTranslate 0 1 5\nRotate 45 1 0 0\n\
             Torus 3.0 1.0 0.0 360.0 360.0\nAttributeEnd\nWorldEnd\n",
        );
        let d = &s.desc;
        assert!(matches!(
            d.objects[0].mesh,
            MeshDesc::Torus { r_major, r_minor, phi_min, phi_max, theta_max }
                if (r_major, r_minor, phi_min, phi_max, theta_max) == (3.0, 1.0, 0.0, 360.0, 360.0)
        ));
        // mirror · T(0, 1, 5) · Rx(45°), by hand: c = s = √½.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        close(
            matrix(d, 0),
            [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, h, -h, 1.0],
                [0.0, -h, -h, -5.0],
                [0.0, 0.0, 0.0, 1.0],
            ],
        );
        let at = |p: &str| {
            s.paths
                .iter()
                .rev()
                .find(|(q, _)| q == p)
                .map(|(_, l)| l.pos)
        };
        assert_eq!(
            at("objects[0].mesh.Torus.r_minor"),
            Some(Pos {
                line: 5,
                column: 11
            })
        );
        assert_eq!(at("objects[0]"), Some(Pos { line: 5, column: 1 }));
    }

    #[test]
    fn sphere_parameters_and_attribute_stack() {
        let s = read(
            "WorldBegin\nColor [1 0 0]\nAttributeBegin\nColor [0 1 0]\nSurface \"matte\" \"Kd\" 0.5\n\
             Sphere 2 -1 1.5 270\nAttributeEnd\nSphere 1 -1 1 360\nWorldEnd\n",
        );
        let d = &s.desc;
        assert!(matches!(
            d.objects[0].mesh,
            MeshDesc::Sphere { radius, z_min: Some(a), z_max: Some(b), theta_max }
                if (radius, a, b, theta_max) == (2.0, -1.0, 1.5, 270.0)
        ));
        // matte as the RI formula: Cs·(Ka·ambient() + Kd·diffuse), Ka 1 by default.
        assert!(matches!(
            d.materials[0].shader,
            ShaderDesc::Local { ka, kd, color, specular, .. }
                if (ka, kd, color, specular) == (1.0, 0.5, (0.0, 1.0, 0.0), (0.0, 0.0, 0.0))
        ));
        // Outside the block: red, defaultsurface with the RI defaults Ka 0.2, Kd 0.8.
        assert!(matches!(
            d.materials[1].shader,
            ShaderDesc::DefaultSurface { ka, kd, color } if (ka, kd, color) == (0.2, 0.8, (1.0, 0.0, 0.0))
        ));
        assert!(d.materials.iter().all(|m| m.two_sided));
    }

    #[test]
    fn camera_transform_before_world_and_lights() {
        let s = read(
            "Projection \"perspective\" \"fov\" [ 30 ]\nLightSource \"pointlight\" 0\n\
             Translate 0 0 7\nWorldBegin\nTranslate 1 0 0\n\
             LightSource \"spotlight\" 1 \"from\" [0 0 2] \"coneangle\" 0.35 \"to\" [0 0 3]\n\
             WorldEnd\n",
        );
        let d = &s.desc;
        // Declared in camera space at the eye (RIB world z = −7, ours +7).
        assert!(
            matches!(d.lights[0].kind, LightKindDesc::Point { position } if position == (0.0, 0.0, 7.0))
        );
        let LightKindDesc::Spot {
            position,
            target,
            cone_angle,
            penumbra,
            beam_distribution,
        } = d.lights[1].kind
        else {
            panic!("{:?}", d.lights[1].kind)
        };
        assert_eq!(position, (1.0, 0.0, -2.0));
        assert_eq!(target, (1.0, 0.0, -3.0));
        assert!((cone_angle - 0.35f64.to_degrees()).abs() < 1e-12);
        assert!((penumbra - 5.0).abs() < 1e-12);
        assert_eq!(beam_distribution, 2.0);
        assert!(!d.lights[0].shadows);
        assert!((d.cameras[0].fov_y - 30.0).abs() < 1e-12);
    }

    #[test]
    fn patch_mesh_with_basis_equals_its_ron() {
        let s = read(
            "Basis \"b-spline\" 1 \"b-spline\" 1\nWorldBegin\n\
             PatchMesh \"bicubic\" 4 \"nonperiodic\" 4 \"periodic\" \"P\" [\
             0 0 0 1 0 0 2 0 0 3 0 0 0 1 0 1 1 1 2 1 0 3 1 0 \
             0 2 0 1 2 0 2 2 1 3 2 0 0 3 0 1 3 0 2 3 0 3 3 0]\nWorldEnd\n",
        );
        let ron = "PatchMesh(basis: BSpline, nu: 4, nv: 4, u_wrap: false, v_wrap: true, points: [\
             (0, 0, 0), (1, 0, 0), (2, 0, 0), (3, 0, 0), (0, 1, 0), (1, 1, 1), (2, 1, 0), (3, 1, 0), \
             (0, 2, 0), (1, 2, 0), (2, 2, 1), (3, 2, 0), (0, 3, 0), (1, 3, 0), (2, 3, 0), (3, 3, 0)])";
        let expected: MeshDesc = ron::from_str(ron).unwrap();
        assert_eq!(
            format!("{:?}", s.desc.objects[0].mesh),
            format!("{expected:?}")
        );
    }

    #[test]
    fn standard_shaders_become_the_ri_formulas() {
        let s = read(
            "WorldBegin\nColor [0.5 0.25 1]\n\
             AttributeBegin\nSurface \"matte\" \"Kd\" 0.7\nSphere 1 -1 1 360\nAttributeEnd\n\
             AttributeBegin\nSurface \"metal\" \"Ks\" 0.5 \"roughness\" 0.2\nSphere 1 -1 1 360\nAttributeEnd\n\
             AttributeBegin\nSurface \"shinymetal\" \"Kr\" 0.5\nSphere 1 -1 1 360\nAttributeEnd\n\
             AttributeBegin\nSurface \"shinymetal\" \"Kr\" 0.5 \"texturename\" \"env.tex\"\nSphere 1 -1 1 360\nAttributeEnd\n\
             AttributeBegin\nSurface \"plastic\" \"Ks\" 0.25 \"specularcolor\" [1 0 0.5]\nSphere 1 -1 1 360\nAttributeEnd\n\
             WorldEnd\n",
        );
        let cs = (0.5, 0.25, 1.0);
        let local = |i: usize| match s.desc.materials[i].shader {
            ShaderDesc::Local {
                color,
                ka,
                kd,
                specular,
                lobe: crate::scene::desc::LocalLobeDesc::RenderMan { roughness },
                reflection,
                ambient,
            } => (color, ka, kd, specular, roughness, reflection, ambient),
            ref other => panic!("{other:?}"),
        };
        let z = (0.0, 0.0, 0.0);
        // matte: Cs·(Ka·ambient() + Kd·diffuse), RI defaults Ka 1.
        assert_eq!(local(0), (cs, 1.0, 0.7, z, 0.1, z, z));
        // metal: no diffuse, the highlight tinted by Cs.
        assert_eq!(local(1), (cs, 1.0, 0.0, (0.25, 0.125, 0.5), 0.2, z, z));
        // shinymetal without a map: environment("") is black; with one, Kr·Cs traced.
        assert_eq!(local(2), (cs, 1.0, 0.0, cs, 0.1, z, z));
        assert_eq!(local(3), (cs, 1.0, 0.0, cs, 0.1, (0.25, 0.125, 0.5), z));
        // plastic: Ka 1, Kd 0.5, Ks·specularcolor.
        assert_eq!(local(4), (cs, 1.0, 0.5, (0.25, 0.0, 0.125), 0.1, z, z));
        let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
        assert_eq!(
            w,
            vec![
                "t.rib:16:45: warning: \"texturename\" \"env.tex\" of \"shinymetal\": a traced \
                 mirror reflection stands in for the environment map"
            ]
        );
        let at = |p: &str| {
            s.paths
                .iter()
                .rev()
                .find(|(q, _)| q == p)
                .map(|(_, l)| (l.pos.line, l.pos.column))
        };
        assert_eq!(at("materials[1].shader.Local.specular"), Some((8, 22)));
        assert_eq!(
            at("materials[1].shader.Local.lobe.RenderMan.roughness"),
            Some((8, 38))
        );
    }

    #[test]
    fn ambientlight_is_an_ambient_light() {
        let s = read(
            "WorldBegin\nLightSource \"ambientlight\" 1 \"intensity\" 0.25 \
             \"lightcolor\" [1 0.5 0]\nSphere 1 -1 1 360\nWorldEnd\n",
        );
        let l = &s.desc.lights[0];
        assert!(matches!(l.kind, LightKindDesc::Ambient));
        assert_eq!((l.intensity, l.color), (0.25, (1.0, 0.5, 0.0)));
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    }

    #[test]
    fn off_centre_screen_window_is_a_shifted_pinhole() {
        let s = read(
            "Format 200 100 1\nScreenWindow 0 2 -0.5 0.5\nProjection \"perspective\" \
             \"fov\" [90]\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\n",
        );
        let c = &s.desc.cameras[0];
        // Half-height 0.5 of the window at tan(45°) = 1: fov_y = 2·atan(0.5).
        assert!((c.fov_y - 2.0 * 0.5f64.atan().to_degrees()).abs() < 1e-12);
        assert_eq!(c.aspect, Some(2.0));
        // Centre (1, 0) in half-heights of 0.5: 2 to the right.
        assert!(matches!(
            c.lens[..],
            [crate::scene::desc::LensDesc::Shift { x, y }] if (x, y) == (2.0, 0.0)
        ));
    }

    #[test]
    fn transform_blocks_and_a_mirroring_camera() {
        // The camera mirrors already (Scale 1 1 -1): no world mirror. Inside the world a
        // TransformBegin/End around a ConcatTransform, then Scale: only the scale remains.
        let s = read(
            "Scale 1 1 -1\nWorldBegin\nTranslate 1 2 3\nTransformBegin\n\
             ConcatTransform [2 0 0 0  0 1 0 0  0 0 1 0  5 0 0 1]\nSphere 1 -1 1 360\n\
             TransformEnd\nScale 2 2 2\nSphere 1 -1 1 360\nWorldEnd\n",
        );
        // T(1, 2, 3) · (x ↦ 2x + 5 in RIB row-vector form: column form [[2,0,0,5],…]).
        close(
            matrix(&s.desc, 0),
            [
                [2.0, 0.0, 0.0, 6.0],
                [0.0, 1.0, 0.0, 2.0],
                [0.0, 0.0, 1.0, 3.0],
                [0.0, 0.0, 0.0, 1.0],
            ],
        );
        close(
            matrix(&s.desc, 1),
            [
                [2.0, 0.0, 0.0, 1.0],
                [0.0, 2.0, 0.0, 2.0],
                [0.0, 0.0, 2.0, 3.0],
                [0.0, 0.0, 0.0, 1.0],
            ],
        );
    }

    #[test]
    fn paraboloid_and_hyperboloid_are_nurbs() {
        let s = read("WorldBegin\nParaboloid 1 0 2 360\nHyperboloid 1 0 -1 0 1 1 180\nWorldEnd\n");
        assert!(matches!(
            s.desc.objects[0].mesh,
            MeshDesc::Nurbs {
                degree_u: 2,
                degree_v: 2,
                count_u: 9,
                count_v: 3,
                ..
            }
        ));
        assert!(matches!(
            s.desc.objects[1].mesh,
            MeshDesc::Nurbs {
                degree_u: 2,
                degree_v: 1,
                count_u: 5,
                count_v: 2,
                ..
            }
        ));
        assert!(s.warnings.is_empty(), "{:?}", s.warnings);
    }

    #[test]
    fn ignored_requests_are_located_warnings() {
        let s = read("Hider \"photon\" \"emit\" 1000000\nWorldBegin\nAttribute \"visibility\" \"integer camera\" [1]\nWorldEnd\n");
        let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
        assert_eq!(
            w,
            vec![
                "t.rib:1:1: warning: ignored request \"Hider\"",
                "t.rib:3:24: warning: ignored Attribute \"visibility\" \"camera\"",
            ]
        );
    }
}
