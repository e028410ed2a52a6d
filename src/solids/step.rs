//! STEP AP214 (ISO 10303-214, `automotive_design`) files of the parts and the assembly.
//!
//! The B-rep of each part (its faces, edges, vertices, planes and the rational B-spline
//! cylinders of its arcs) is built and written by the `truck` kernel (`truck-modeling`,
//! `truck-stepio`). truck writes one unnamed product per file, so the product structure
//! around those solids is written here: a named product per part, the assembly's product,
//! and one `NEXT_ASSEMBLY_USAGE_OCCURRENCE` with its placement per instance (the pattern
//! OpenCascade and the CAD systems on it write and read).

use super::profile::{arc_centre, ends, Profile};
use super::{Assembly, Part};
use crate::{Error, Result};
use noncirc_core::Vec2;
use std::f64::consts::FRAC_PI_2;
use std::fmt::Write as _;
use truck_modeling::{
    builder, BSplineCurve, Curve, Edge, KnotVec, NurbsCurve, Point3, Solid, Vector3, Vector4, Wire,
};

/// The arc from `a` to `b` with `bulge` (mm; DXF's sign) as a rational quadratic B-spline,
/// exactly: a Bézier segment per quarter turn or less, each with its tangents' meeting
/// point as the middle control point, of weight cos(φ/2). (truck's `circle_arc` finds the
/// centre through a Gram determinant that loses digits on the nearly straight arcs of a
/// flank.)
fn arc(a: Vec2, b: Vec2, bulge: f64) -> NurbsCurve<Vector4> {
    let swept = 4.0 * bulge.atan();
    let k = (swept.abs() / FRAC_PI_2).ceil().max(1.0) as usize;
    let c = arc_centre(a, b, bulge);
    let u = a - c;
    let point = |i: usize| match i {
        0 => a,
        i if i == k => b,
        i => {
            let (s, co) = (swept * i as f64 / k as f64).sin_cos();
            c + u.rotated(Vec2::new(co, s))
        }
    };
    let phi = swept / k as f64;
    let w = (0.5 * phi).cos();
    let mut control = vec![Vector4::new(a.x, a.y, 0.0, 1.0)];
    let mut knots = vec![0.0; 3];
    for i in 0..k {
        let (p, q) = (point(i), point(i + 1));
        let d = q - p;
        let t = (p + q) * 0.5 + Vec2::new(d.y, -d.x) * (0.5 * (0.5 * phi).tan());
        control.push(Vector4::new(t.x * w, t.y * w, 0.0, w));
        control.push(Vector4::new(q.x, q.y, 0.0, 1.0));
        let knot = (i + 1) as f64 / k as f64;
        knots.extend(if i + 1 == k {
            [1.0; 3].to_vec()
        } else {
            vec![knot; 2]
        });
    }
    NurbsCurve::new(BSplineCurve::new(KnotVec::from(knots), control))
}
use truck_stepio::out::StepModel;

/// The solid of `profile` extruded by `thickness` (mm) along +z from z = 0.
pub fn extrude(profile: &Profile, thickness: f64, name: &str) -> Result<Solid> {
    let wire = |loop_: &[crate::cad::Piece]| -> Wire {
        let vertices: Vec<_> = (loop_.iter())
            .map(|p| builder::vertex(Point3::new(p.start.x, p.start.y, 0.0)))
            .collect();
        let n = vertices.len();
        (0..n)
            .map(|i| {
                let (v, w) = (&vertices[i], &vertices[(i + 1) % n]);
                let (a, b) = ends(loop_, i);
                match loop_[i].bulge {
                    0.0 => builder::line(v, w),
                    bulge => Edge::new(v, w, Curve::NurbsCurve(arc(a, b, bulge))),
                }
            })
            .collect()
    };
    let wires: Vec<Wire> = std::iter::once(&profile.outer)
        .chain(&profile.holes)
        .map(|l| wire(l))
        .collect();
    let face = builder::try_attach_plane(&wires)
        .map_err(|e| Error::Input(format!("the solid of {name} cannot be built: {e}")))?;
    Ok(builder::tsweep(&face, Vector3::new(0.0, 0.0, thickness)))
}

/// A STEP string: the quote doubled.
fn text(s: &str) -> String {
    format!("'{}'", s.replace('\'', "''"))
}

/// A real in STEP's form: a decimal point always (`12.0`, `1.E-07`), the shortest digits
/// that read back as `x`.
fn real(x: f64) -> String {
    let s = format!("{x:?}");
    let (mantissa, exponent) = match s.split_once('e') {
        Some((m, e)) => (m, Some(e)),
        None => (s.as_str(), None),
    };
    let point = if mantissa.contains('.') { "" } else { "." };
    match exponent {
        Some(e) => format!("{mantissa}{point}E{e}"),
        None => format!("{mantissa}{point}"),
    }
}

/// The entities of one exchange structure, numbered as they are added.
struct Entities {
    body: String,
    next: usize,
}

impl Entities {
    fn add(&mut self, entity: &str) -> usize {
        let id = self.next;
        let _ = writeln!(self.body, "#{id} = {entity};");
        self.next += 1;
        id
    }

    /// An axis placement at `at` (mm) turned by `angle` (rad) about z.
    fn placement(&mut self, at: [f64; 3], angle: f64) -> usize {
        let p = self.add(&format!(
            "CARTESIAN_POINT('',({},{},{}))",
            real(at[0]),
            real(at[1]),
            real(at[2])
        ));
        let z = self.add("DIRECTION('',(0.,0.,1.))");
        let (s, c) = angle.sin_cos();
        let x = self.add(&format!("DIRECTION('',({},{},0.))", real(c), real(s)));
        self.add(&format!("AXIS2_PLACEMENT_3D('',#{p},#{z},#{x})"))
    }

    /// truck's B-rep of `solid` renumbered into this structure, named; its
    /// `MANIFOLD_SOLID_BREP`'s number.
    fn brep(&mut self, solid: &Solid, name: &str) -> usize {
        let compressed = solid.compress();
        let written = StepModel::from(&compressed).to_string();
        // truck numbers its context #1–#15 and the solid from #16 on.
        let from = written
            .find("#16 =")
            .expect("truck writes the solid from #16");
        let geometry = &written[from..];
        let base = self.next;
        let mut out = String::with_capacity(geometry.len() + 64);
        let mut highest = 0;
        let mut chars = geometry.char_indices().peekable();
        while let Some((i, c)) = chars.next() {
            if c != '#' {
                out.push(c);
                continue;
            }
            let mut end = i + 1;
            while let Some(&(j, d)) = chars.peek() {
                if !d.is_ascii_digit() {
                    break;
                }
                end = j + 1;
                chars.next();
            }
            let n: usize = geometry[i + 1..end].parse().expect("a reference");
            assert!(n >= 16, "truck's solid refers to its context #{n}");
            highest = highest.max(n);
            let _ = write!(out, "#{}", n - 16 + base);
        }
        let out = out.replacen(
            "MANIFOLD_SOLID_BREP('',",
            &format!("MANIFOLD_SOLID_BREP({},", text(name)),
            1,
        );
        self.body.push_str(&out);
        if !out.ends_with('\n') {
            self.body.push('\n');
        }
        self.next = base + highest - 15;
        base
    }
}

/// The context every representation shares: units (mm, rad, sr) and the 1 µm uncertainty.
struct Context {
    product: usize,
    definition: usize,
    geometry: usize,
}

fn context(e: &mut Entities) -> Context {
    let app = e.add("APPLICATION_CONTEXT('core data for automotive mechanical design processes')");
    e.add(&format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ));
    let product = e.add(&format!("PRODUCT_CONTEXT('',#{app},'mechanical')"));
    let definition = e.add(&format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ));
    let mm = e.add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )");
    let rad = e.add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )");
    let sr = e.add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )");
    let tol = e.add(&format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-06),#{mm},'distance_accuracy_value','confusion accuracy')"
    ));
    let geometry = e.add(&format!(
        "( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{tol})) \
         GLOBAL_UNIT_ASSIGNED_CONTEXT((#{mm},#{rad},#{sr})) REPRESENTATION_CONTEXT('','3D') )"
    ));
    Context {
        product,
        definition,
        geometry,
    }
}

/// A named product and its definition; the definition's number.
fn product(e: &mut Entities, c: &Context, name: &str, category: &str) -> (usize, usize) {
    let p = e.add(&format!(
        "PRODUCT({0},{0},'',(#{1}))",
        text(name),
        c.product
    ));
    e.add(&format!(
        "PRODUCT_RELATED_PRODUCT_CATEGORY('{category}',$,(#{p}))"
    ));
    let f = e.add(&format!("PRODUCT_DEFINITION_FORMATION('','',#{p})"));
    let d = e.add(&format!(
        "PRODUCT_DEFINITION('design','',#{f},#{})",
        c.definition
    ));
    let shape = e.add(&format!("PRODUCT_DEFINITION_SHAPE('','',#{d})"));
    (d, shape)
}

/// A part's product with its solid; its definition and its representation's number and
/// origin.
fn part(e: &mut Entities, c: &Context, part: &Part) -> Result<(usize, usize, usize)> {
    let solid = extrude(&part.profile, part.thickness_mm, &part.name)?;
    let (d, shape) = product(e, c, &part.name, "part");
    let brep = e.brep(&solid, &part.name);
    let origin = e.placement([0.0; 3], 0.0);
    let rep = e.add(&format!(
        "ADVANCED_BREP_SHAPE_REPRESENTATION({},(#{origin},#{brep}),#{})",
        text(&part.name),
        c.geometry
    ));
    e.add(&format!("SHAPE_DEFINITION_REPRESENTATION(#{shape},#{rep})"));
    Ok((d, rep, origin))
}

/// The exchange structure around `entities`: the header (a fixed time stamp, so that the
/// same design gives the same file) and the data section.
fn file(name: &str, description: &str, e: Entities) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(({}),'2;1');\n\
         FILE_NAME({},'1970-01-01T00:00:00',('noncirc'),(''),'noncirc {}','noncirc','');\n\
         FILE_SCHEMA(('AUTOMOTIVE_DESIGN {{ 1 0 10303 214 1 1 1 1 }}'));\nENDSEC;\nDATA;\n{}ENDSEC;\nEND-ISO-10303-21;\n",
        text(description),
        text(name),
        env!("CARGO_PKG_VERSION"),
        e.body
    )
}

/// One part alone, in its own frame: `<part>.step`.
pub fn part_file(part: &Part) -> Result<String> {
    let mut e = Entities {
        body: String::new(),
        next: 1,
    };
    let c = context(&mut e);
    self::part(&mut e, &c, part)?;
    Ok(file(
        &format!("{}.step", part.name),
        &format!("noncirc part {}", part.name),
        e,
    ))
}

/// The assembly: each part once, and each instance of it placed (mm, about z), named.
pub fn assembly_file(asm: &Assembly) -> Result<String> {
    let mut e = Entities {
        body: String::new(),
        next: 1,
    };
    let c = context(&mut e);
    let (top, top_shape) = product(&mut e, &c, &asm.name, "assembly");
    let origin = e.placement([0.0; 3], 0.0);
    let placements: Vec<usize> = (asm.instances.iter())
        .map(|i| e.placement(i.at_mm, i.angle_deg.to_radians()))
        .collect();
    let items: Vec<String> = std::iter::once(origin)
        .chain(placements.iter().copied())
        .map(|n| format!("#{n}"))
        .collect();
    let top_rep = e.add(&format!(
        "SHAPE_REPRESENTATION({},({}),#{})",
        text(&asm.name),
        items.join(","),
        c.geometry
    ));
    e.add(&format!(
        "SHAPE_DEFINITION_REPRESENTATION(#{top_shape},#{top_rep})"
    ));
    let parts: Vec<(usize, usize, usize)> = (asm.parts.iter())
        .map(|p| part(&mut e, &c, p))
        .collect::<Result<_>>()?;
    for (k, (instance, placement)) in asm.instances.iter().zip(placements).enumerate() {
        let (definition, rep, part_origin) = parts[instance.part];
        let usage = e.add(&format!(
            "NEXT_ASSEMBLY_USAGE_OCCURRENCE('{}',{},'',#{top},#{definition},$)",
            k + 1,
            text(&instance.name)
        ));
        let shape = e.add(&format!("PRODUCT_DEFINITION_SHAPE('','',#{usage})"));
        let transform = e.add(&format!(
            "ITEM_DEFINED_TRANSFORMATION('','',#{part_origin},#{placement})"
        ));
        let relation = e.add(&format!(
            "( REPRESENTATION_RELATIONSHIP('','',#{rep},#{top_rep}) \
             REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION(#{transform}) \
             SHAPE_REPRESENTATION_RELATIONSHIP() )"
        ));
        e.add(&format!(
            "CONTEXT_DEPENDENT_SHAPE_REPRESENTATION(#{relation},#{shape})"
        ));
    }
    Ok(file(
        &format!("{}.step", asm.name),
        &format!("noncirc assembly {}", asm.name),
        e,
    ))
}

#[cfg(test)]
mod tests {
    use super::real;

    #[test]
    fn reals_have_a_decimal_point_and_read_back() {
        for (x, text) in [
            (12.0, "12.0"),
            (1e-7, "1.E-7"),
            (-3.5e-17, "-3.5E-17"),
            (0.1, "0.1"),
        ] {
            assert_eq!(real(x), text);
            assert_eq!(real(x).replace(".E", ".0E").parse::<f64>().unwrap(), x);
        }
    }
}
