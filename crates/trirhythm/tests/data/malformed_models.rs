// Malformed model files, each with the dotted field its refusal must name. Shared by
// `crates/trirhythm/tests/model_file.rs` (the library's refusal) and
// `crates/trirhythm-cli/tests/model.rs` (exit 2, the field named, no output file).
// Each is the base file below with one change.

/// A valid file of the paper family (Fig. 13(a)'s set).
pub const BASE: &str = r#"format = 1
[leading]
lambda = 0.998
[damping]
mu0 = 0.005
coefficients = [1.0, -1.0, 0.144, -0.005, 5.862e-5, -2.13e-7]
[restoring]
omega0 = 1.0
[[wall]]
position = 0.0
keep = "above"
restitution = 0.99
[noise.additive]
intensity = 0.1
correlation_time = 0.5
[start]
u0 = 1.0
v0 = 0.0
"#;

/// (field named, text replaced in [`BASE`], replacement).
pub const MALFORMED: &[(&str, &str, &str)] = &[
    ("format", "format = 1", ""),
    ("format", "format = 1", "format = 2"),
    ("leading.lambda", "lambda = 0.998", "lambda = 1.5"),
    ("leading.lambda", "lambda = 0.998", "lambda = 0.0"),
    ("leading.lambda", "lambda = 0.998", "lambda = \"one\""),
    ("leading.order", "lambda = 0.998", "lambda = 0.998\norder = 2"),
    ("damping.mu0", "mu0 = 0.005", "mu0 = -0.1"),
    ("damping.mu0", "mu0 = 0.005\n", ""),
    ("damping.coefficients.2", "0.144,", "1e30,"),
    ("damping.coefficients", "coefficients = [1.0, -1.0, 0.144, -0.005, 5.862e-5, -2.13e-7]", "coefficients = []"),
    ("damping.rayleigh.0", "mu0 = 0.005", "mu0 = 0.005\nrayleigh = [nan]"),
    ("restoring.omega0", "omega0 = 1.0", "omega0 = 0.0"),
    ("restoring.cubic", "omega0 = 1.0", "omega0 = 1.0\ncubic = inf"),
    ("wall.0.restitution", "restitution = 0.99", "restitution = 1.2"),
    ("wall.0.restitution.speed", "restitution = 0.99", "restitution = { r0 = 0.9, r_fast = 0.5, speed = 0.0 }"),
    ("wall.0.keep", "keep = \"above\"", "keep = \"left\""),
    ("wall.1.position", "[noise.additive]", "[[wall]]\nposition = -1.0\nkeep = \"below\"\nrestitution = 0.9\n[noise.additive]"),
    ("wall.0.restitution", "restitution = 0.99", "restitution = \"high\""),
    ("start.u0", "u0 = 1.0", "u0 = -0.5"),
    ("noise.additive.intensity", "intensity = 0.1", "intensity = -1.0"),
    ("noise.additive.correlation_time", "correlation_time = 0.5", "correlation_time = -0.5"),
    ("noise.correlation", "[noise.additive]", "[noise]\ncorrelation = 0.5\n[noise.additive]"),
    ("fractional.0.order", "[noise.additive]", "[[fractional]]\ncoefficient = 0.1\norder = 1.5\n[noise.additive]"),
    ("forcing.frequency", "[noise.additive]", "[forcing]\namplitude = 0.1\nfrequency = -1.0\n[noise.additive]"),
    ("noise.additive.colour", "[start]", "colour = \"red\"\n[start]"),
    ("(syntax)", "mu0 = 0.005", "mu0 = = 0.005"),
];

/// [`BASE`] with the change of `MALFORMED[i]` applied (the text to replace occurs in it).
pub fn malformed(i: usize) -> String {
    let (_, from, to) = MALFORMED[i];
    assert!(BASE.contains(from), "case {i}: `{from}` not in the base file");
    BASE.replacen(from, to, 1)
}
