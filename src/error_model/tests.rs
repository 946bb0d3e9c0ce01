use super::effects::*;
use super::*;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-12
}

fn sample(x: f64, z: f64) -> Sample {
    Sample::at_rest(Xz::new(x, z), 0.0)
}

#[test]
fn effects_follow_their_formulas() {
    let s = Sample { velocity: Xz::new(600.0, 0.0), t_min: 54.59, cut_length_m: 2.0, ..sample(20.0, -50.0) };
    let d = |e: Effect| e.displacement(&s);
    assert_eq!(d(Effect::ToolOffsetX(ToolOffsetX { d: 0.003, axis: X })), Xz::new(0.003, 0.0));
    assert_eq!(d(Effect::ToolOffsetZ(ToolOffsetZ { d: -0.002, axis: Z })), Xz::new(0.0, -0.002));
    assert!(close(d(Effect::ScaleX(ScaleX { ppm: 50.0, axis: X })).x, 20.0 * 50e-6));
    assert!(close(d(Effect::ScaleZ(ScaleZ { ppm: 50.0, axis: Z })).z, -50.0 * 50e-6));
    assert!(close(d(Effect::Squareness(Squareness { urad: 20.0 })).x, -50.0 * 20e-6));
    // 600 mm/min is 0.01 mm/ms: 2 ms of lag leave X 0.02 mm behind.
    assert!(close(d(Effect::ServoMismatch(ServoMismatch { dt_ms: 2.0 })).x, -0.02));
    // One time constant: 1 − 1/e of the growth.
    let thermal = d(Effect::ThermalZ(ThermalZ { amp: 0.01, tau_min: 54.59, axis: Z })).z;
    assert!(close(thermal, 0.01 * (1.0 - (-1.0f64).exp())));
    assert!(close(d(Effect::ToolWear(ToolWear { um_per_m: 1.5 })).x, 0.003));
    let cyclic = d(Effect::CyclicZ(CyclicZ { amp: 0.002, pitch: 11.94, phase: 0.5, axis: Z })).z;
    assert!(close(cyclic, 0.002 * (std::f64::consts::TAU * -50.0 / 11.94 + 0.5).sin()));
    // A bow of 1e-6 mm per mm² and 1e-8 per mm³ at z = −50.
    let bow = d(Effect::StraightnessX(StraightnessX { coeffs: vec![1e-6, 1e-8], axis: X })).x;
    assert!(close(bow, 1e-6 * 2500.0 + 1e-8 * -125000.0));
}

#[test]
fn backlash_follows_the_last_direction_and_persists_at_rest() {
    let effect = Effect::BacklashX(BacklashX { b: 0.004, axis: X });
    let model = ErrorModel { effects: vec![effect.clone()], ..ErrorModel::default() };
    let mut tracker = Tracker::new(Xz::new(10.0, 0.0), model.play());
    let zero = Xz::new(0.0, 0.0);
    // Reached from +: the slide lags 0.002 below its command.
    assert!(close(effect.displacement(&tracker.sample(0.0, zero, 1, zero, zero)).x, -0.002));
    tracker.advance(Xz::new(8.0, 0.0), 1, false);
    let moving_down = tracker.sample(0.0, Xz::new(-100.0, 0.0), 1, zero, zero);
    assert!(close(effect.displacement(&moving_down).x, 0.002));
    // Z moves; X rests and keeps its offset.
    tracker.advance(Xz::new(8.0, -5.0), 1, true);
    let resting = tracker.sample(0.0, Xz::new(0.0, -100.0), 1, zero, zero);
    assert!(close(effect.displacement(&resting).x, 0.002));
    // A command back up by less than the play moves nothing: the slide stays at 8.002.
    tracker.advance(Xz::new(8.003, -5.0), 1, false);
    let inside = tracker.sample(0.0, zero, 1, zero, zero);
    assert!(close(inside.at.x + effect.displacement(&inside).x, 8.002));
    assert_eq!(inside.direction.x, -1);
    tracker.advance(Xz::new(9.0, -5.0), 1, true);
    let up = tracker.sample(0.0, Xz::new(100.0, 0.0), 1, zero, zero);
    assert!(close(effect.displacement(&up).x, -0.002));
    assert_eq!(up.direction.x, 1);
    // The cut length counts cutting travel only: 5 mm + 0.997 mm.
    assert!(close(up.cut_length_m, 0.005997));
}

#[test]
fn reversal_spike_decays_with_travel_since_the_reversal() {
    let effect = Effect::ReversalSpikeX(ReversalSpikeX { h: 0.003, decay_mm: 0.5, axis: X });
    let mut tracker = Tracker::new(Xz::new(10.0, 0.0), Xz::new(0.0, 0.0));
    tracker.advance(Xz::new(12.0, 0.0), 1, false);
    tracker.advance(Xz::new(11.5, 0.0), 1, false);
    let s = tracker.sample(0.0, Xz::new(0.0, 0.0), 1, Xz::new(0.0, 0.0), Xz::new(0.0, 0.0));
    assert!(close(effect.displacement(&s).x, -0.003 * (-1.0f64).exp()));
}

#[test]
fn nose_radius_error_leaves_diameters_and_faces_and_grows_on_chamfers() {
    let effect = Effect::NoseRadius(NoseRadius { dr: 0.1 });
    // Tip 3 (outside turning toward the chuck): the imaginary tip is at (−r, −r).
    let tip = Xz::new(-1.0, -1.0);
    let on = |normal: Xz| Sample { normal, tip, ..sample(10.0, -5.0) };
    let diameter = effect.displacement(&on(Xz::new(1.0, 0.0)));
    let normal_part = |d: Xz, n: Xz| d.x * n.x + d.z * n.z;
    assert!(close(normal_part(diameter, Xz::new(1.0, 0.0)), 0.0));
    let face = effect.displacement(&on(Xz::new(0.0, 1.0)));
    assert!(close(normal_part(face, Xz::new(0.0, 1.0)), 0.0));
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let chamfer = effect.displacement(&on(Xz::new(h, h)));
    assert!((normal_part(chamfer, Xz::new(h, h)) - 0.1 * (2f64.sqrt() - 1.0)).abs() < 1e-12);
}

#[test]
fn the_model_file_reads_effects_and_rejects_unknown_names_and_parameters() {
    let spec = model_file::ModelSpec::from_toml(
        "[machine]\nunits = \"mm\"\n[model]\nstart_min = 30\n[[effect]]\nkind = \"backlash_z\"\nb = 0.004\n\
         [[effect]]\nkind = \"thermal_x\"\namp = 0.01\ntau_min = 54.59\n",
    )
    .unwrap();
    let model = spec.build(|_| Err("no files".to_string())).unwrap();
    assert_eq!(model.effects.len(), 2);
    assert_eq!(model.start_min, 30.0);
    assert_eq!(model.effects[0].name(), "backlash_z");
    assert!(model_file::ModelSpec::from_toml("[[effect]]\nkind = \"backlash_y\"\nb = 1\n").is_err());
    assert!(model_file::ModelSpec::from_toml("[[effect]]\nkind = \"backlash_x\"\nbb = 1\n").is_err());
    assert!(model_file::ModelSpec::from_toml("[[effects]]\nkind = \"backlash_x\"\nb = 1\n").is_err());
}

#[test]
fn htm_composes_slide_errors_as_eq_8_12() {
    let x = interferometer::parse(
        "target_mm,direction,linear_mm,straightness_mm,angular_deg\n0,up,0.001,0.002,0.01\n100,up,0.003,0.004,0.01\n",
    )
    .unwrap();
    let z = interferometer::parse(
        "target_mm,direction,linear_mm,straightness_mm,angular_deg\n-100,up,-0.002,0.0005,0.02\n0,up,0,0.0015,0.02\n",
    )
    .unwrap();
    let tables = htm::AxisTables { x, z, abbe_y_mm: 5.0 };
    let s = sample(50.0, -50.0);
    let d = tables.displacement(&s);
    let (pitch, yaw) = (0.01f64.to_radians(), 0.02f64.to_radians());
    let (linear_x, straightness_xz, linear_z, straightness_zx) = (0.002, 0.003, -0.001, 0.001);
    assert!(close(d.x, linear_x + straightness_zx - pitch * 5.0 + yaw * pitch * (-50.0 + linear_z)));
    assert!(close(d.z, linear_z + straightness_xz + yaw * 5.0));
}

/// The largest gap between `f` and its chords `step` apart, over `0..=length`, each chord
/// tried from many starting points.
fn worst_chord_gap(f: impl Fn(f64) -> f64, length: f64, step: f64) -> f64 {
    let mut worst: f64 = 0.0;
    let starts = 400;
    for i in 0..=starts {
        let a = (length - step) * i as f64 / starts as f64;
        let (fa, fb) = (f(a), f(a + step));
        for k in 1..20 {
            let t = k as f64 / 20.0;
            worst = worst.max((f(a + step * t) - (fa + (fb - fa) * t)).abs());
        }
    }
    worst
}

#[test]
fn curved_effects_sampled_at_their_spacing_stay_within_the_allowance_of_the_chords() {
    let allowance = 5e-5;
    let reach = Xz::new(80.0, 300.0);
    let step = |e: &Effect| e.spacing(allowance, reach);
    // Along Z through the screw, along X through the X screw.
    let cyclic_z = Effect::CyclicZ(CyclicZ { amp: 0.004, pitch: 11.94, phase: 0.3, axis: Z });
    let h = step(&cyclic_z).mm;
    assert!((h - 0.6007).abs() < 1e-3, "{h}");
    let gap = worst_chord_gap(|z| cyclic_z.displacement(&sample(20.0, -z)).z, 60.0, h);
    assert!(gap <= allowance * 1.0001 && gap > allowance * 0.9, "{gap}");
    let cyclic_x = Effect::CyclicX(CyclicX { amp: 0.002, pitch: 5.0, phase: 0.0, axis: X });
    let h = step(&cyclic_x).mm;
    let gap = worst_chord_gap(|x| cyclic_x.displacement(&sample(x, -10.0)).x, 40.0, h);
    assert!(gap <= allowance * 1.0001 && gap > allowance * 0.9, "{gap}");
    // A bow, to the farthest Z the program reaches.
    let bow = Effect::StraightnessX(StraightnessX { coeffs: vec![2e-7, 1e-9], axis: X });
    let h = step(&bow).mm;
    let gap = worst_chord_gap(|z| bow.displacement(&sample(20.0, -z)).x, reach.z, h);
    assert!(gap <= allowance * 1.0001 && gap > allowance * 0.5, "{gap}");
    // A reversal spike, along the travel since the reversal.
    let spike = Effect::ReversalSpikeX(ReversalSpikeX { h: 0.003, decay_mm: 0.8, axis: X });
    let h = step(&spike).mm;
    let at = |s: f64| {
        let sample = Sample { since_reversal: Xz::new(s, 0.0), ..sample(20.0, -10.0) };
        spike.displacement(&sample).x
    };
    let gap = worst_chord_gap(at, 10.0, h);
    assert!(gap <= allowance * 1.0001 && gap > allowance * 0.5, "{gap}");
    // Warm-up, in time.
    let thermal = Effect::ThermalZ(ThermalZ { amp: 0.008, tau_min: 54.59, axis: Z });
    let minutes = step(&thermal).minutes;
    assert!((minutes - 54.59 * (8.0 * allowance / 0.008f64).sqrt()).abs() < 1e-9, "{minutes}");
    let gap = worst_chord_gap(|t| thermal.displacement(&Sample { t_min: t, ..sample(20.0, -10.0) }).z, 240.0, minutes);
    assert!(gap <= allowance * 1.0001 && gap > allowance * 0.5, "{gap}");
    // Terms that are affine along a line need no inner sample, and a model of them none.
    for affine in [
        Effect::ScaleZ(ScaleZ { ppm: 30.0, axis: Z }),
        Effect::Squareness(Squareness { urad: 20.0 }),
        Effect::BacklashX(BacklashX { b: 0.004, axis: X }),
        Effect::ServoMismatch(ServoMismatch { dt_ms: 1.0 }),
        Effect::ToolWear(ToolWear { um_per_m: 2.0 }),
    ] {
        assert_eq!(step(&affine), Spacing::ANY, "{}", affine.name());
    }
    let model = ErrorModel {
        effects: vec![Effect::ScaleZ(ScaleZ { ppm: 30.0, axis: Z }), cyclic_z.clone()],
        ..ErrorModel::default()
    };
    assert_eq!(model.spacing(allowance, reach), step(&cyclic_z));
    let tables = ErrorModel { tables: Some(htm::AxisTables::default()), ..ErrorModel::default() };
    assert_eq!(tables.spacing(allowance, reach), Spacing::mm(spacing::TABLE_STEP_MM));
}

#[test]
fn terms_that_turn_with_an_arc_stay_within_the_allowance_at_their_angle_step() {
    let allowance = 5e-5;
    let reach = Xz::new(80.0, 300.0);
    let (centre, radius, feed) = (Xz::new(30.0, -40.0), 12.0, 300.0);
    // The correction of `effect` at angle `a` of a counter-clockwise arc at `feed`.
    let around = |effect: &Effect, a: f64| {
        let at = Xz::new(centre.x + radius * a.sin(), centre.z + radius * a.cos());
        // The tangent of increasing angle, and the normal pointing out of the arc.
        let tangent = Xz::new(a.cos(), -a.sin());
        let normal = Xz::new(a.sin(), a.cos());
        let s = Sample {
            velocity: Xz::new(tangent.x * feed, tangent.z * feed),
            normal,
            tip: Xz::new(-1.0, -1.0),
            ..sample(at.x, at.z)
        };
        let d = effect.displacement(&s);
        (d.x, d.z)
    };
    for effect in [
        Effect::ScaleX(ScaleX { ppm: 40.0, axis: X }),
        Effect::ScaleZ(ScaleZ { ppm: 30.0, axis: Z }),
        Effect::Squareness(Squareness { urad: 25.0 }),
        Effect::ServoMismatch(ServoMismatch { dt_ms: 0.8 }),
        Effect::NoseRadius(NoseRadius { dr: 0.004 }),
    ] {
        let terms = effect.arc_terms(reach);
        let step = terms.radians(radius, feed, allowance);
        assert!(step.is_finite() && step > 0.0, "{}", effect.name());
        for component in [0, 1] {
            let f = |a: f64| {
                let (x, z) = around(&effect, a);
                if component == 0 { x } else { z }
            };
            let gap = worst_chord_gap(f, std::f64::consts::TAU, step);
            assert!(gap <= allowance * 1.0001, "{}: {gap}", effect.name());
        }
        // The bound is not loose by more than the sum of the two axes' shares.
        let gap = (0..2)
            .map(|component| {
                worst_chord_gap(
                    |a| {
                        let (x, z) = around(&effect, a);
                        if component == 0 { x } else { z }
                    },
                    std::f64::consts::TAU,
                    step * 2.0,
                )
            })
            .fold(0.0, f64::max);
        assert!(gap > allowance, "{}: twice the step gives {gap}", effect.name());
    }
    // Terms with nothing that turns with the arc ask no angle step.
    let none = Effect::BacklashZ(BacklashZ { b: 0.003, axis: Z }).arc_terms(reach);
    assert_eq!(none.radians(radius, feed, allowance), f64::INFINITY);
}

#[test]
fn cut_length_is_followed_only_for_a_model_that_wears() {
    let wear = ErrorModel { effects: vec![Effect::ToolWear(ToolWear { um_per_m: 2.0 })], ..ErrorModel::default() };
    let offset =
        ErrorModel { effects: vec![Effect::ToolOffsetX(ToolOffsetX { d: 0.01, axis: X })], ..ErrorModel::default() };
    assert!(wear.wears() && !offset.wears());
    let zero = Xz::new(0.0, 0.0);
    let walk = |model: &ErrorModel| {
        let mut tracker = Tracker::new(Xz::new(10.0, 0.0), model.play()).counting_cut(model.wears());
        tracker.advance(Xz::new(10.0, -30.0), 1, true);
        tracker.sample(0.0, zero, 1, zero, zero).cut_length_m
    };
    assert!(close(walk(&wear), 0.03));
    assert_eq!(walk(&offset), 0.0);
}

proptest::proptest! {
    /// The terms of time evaluated once at a sample's time and taken by `displacement_timed`
    /// give the displacement bit for bit, wherever they stand among the other terms; terms
    /// of time it is not given are evaluated.
    #[test]
    fn terms_of_time_evaluated_once_give_the_same_displacement(
        t_min in -10.0f64..500.0,
        x in -100.0f64..100.0,
        z in -300.0f64..50.0,
        amp_x in -0.02f64..0.02,
        amp_z in -0.02f64..0.02,
        tau in 0.0f64..100.0,
        given in 0usize..3,
    ) {
        let model = ErrorModel {
            tables: None,
            effects: vec![
                Effect::ThermalX(ThermalX { amp: amp_x, tau_min: tau, axis: X }),
                Effect::ScaleZ(ScaleZ { ppm: 30.0, axis: Z }),
                Effect::ToolOffsetX(ToolOffsetX { d: 0.005, axis: X }),
                Effect::ThermalZ(ThermalZ { amp: amp_z, tau_min: tau * 0.7, axis: Z }),
                Effect::Squareness(Squareness { urad: 20.0 }),
            ],
            start_min: 0.0,
        control: None,
        };
        let s = Sample { t_min, ..sample(x, z) };
        let mut terms = Vec::new();
        model.time_terms(t_min, &mut terms);
        proptest::prop_assert_eq!(terms.len(), model.time_term_count());
        proptest::prop_assert_eq!(terms.len(), 2);
        let full = model.displacement(&s);
        let timed = model.displacement_timed(&s, terms.get(..given).unwrap_or_default());
        proptest::prop_assert_eq!(full.x.to_bits(), timed.x.to_bits());
        proptest::prop_assert_eq!(full.z.to_bits(), timed.z.to_bits());
        proptest::prop_assert_eq!(model.actual(&s), model.actual_timed(&s, &terms));
    }
}

/// The text a diagnostic of `text` points at.
fn pointed<'t>(text: &'t str, diagnostic: &crate::diagnostic::Diagnostic) -> &'t str {
    &text[diagnostic.span.start as usize..diagnostic.span.end as usize]
}

#[test]
fn a_model_file_problem_is_placed_at_the_table_and_key_that_hold_it() {
    let text = "[[effect]]\nkind = \"scale_x\"\nppm = 60.0\n\n[[effect]]\nkind = \"backlash_x\"\nb = 0.004\n\n\
                [[effect]]\nkind = \"squareness\"\nuradd = 25.0\n\n[[effect]]\nkind = \"thermal_z\"\namp = \"x\"\n\
                tau_min = 40.0\n";
    let problems = model_file::ModelSpec::read(text).unwrap_err().diagnostics;
    assert_eq!(problems.len(), 2);
    assert_eq!(pointed(text, &problems[0]), "uradd");
    assert_eq!(problems[0].message(), "[[effect]] 3 (squareness) has no key `uradd`");
    assert_eq!(problems[0].hint().as_deref(), Some("did you mean `urad`? the keys are `urad`"));
    assert_eq!(pointed(text, &problems[1]), "\"x\"");
    assert!(problems[1].message().starts_with("`amp` in [[effect]] 4 (thermal_z): invalid type"));
}

#[test]
fn every_number_of_a_model_file_is_checked_when_it_is_read() {
    for (text, at, message) in [
        ("[machine]\nleast_increment = 0\n", "0", "`least_increment` in [machine] is 0"),
        ("[machine]\nleast_increment = nan\n", "nan", "`least_increment` in [machine] is NaN, not a finite number"),
        ("[model]\nstart_min = nan\n", "nan", "`start_min` in [model] is NaN"),
        ("[model]\nabbe_y_mm = 1e300\n", "1e300", "`abbe_y_mm` in [model] is 1e300"),
        ("[[effect]]\nkind = \"backlash_x\"\nb = nan\n", "nan", "`b` in [[effect]] 1 (backlash_x) is NaN"),
        ("[[effect]]\nkind = \"scale_z\"\nppm = inf\n", "inf", "`ppm` in [[effect]] 1 (scale_z) is inf"),
        ("[[effect]]\nkind = \"thermal_x\"\namp = 0.01\ntau_min = nan\n", "nan", "`tau_min` in [[effect]] 1"),
        ("[[effect]]\nkind = \"tool_offset_x\"\ndx = inf\n", "inf", "`dx` in [[effect]] 1"),
        ("[[effect]]\nkind = \"straightness_z\"\ncoeffs = [1e-6, 1e300]\n", "1e300", "`coeffs[1]` in [[effect]] 1"),
        ("[[effect]]\nkind = \"cyclic_z\"\namp = 0.004\npitch = 0\nphase = 0\n", "0", "`pitch` in [[effect]] 1"),
        ("[machine]\ntravel = { x_min = 5, x_max = 1, z_min = 0, z_max = 1 }\n", "1", "`x_max` in [machine.travel]"),
    ] {
        let problems = model_file::ModelSpec::read(text).unwrap_err().diagnostics;
        assert_eq!(problems.len(), 1, "{text}");
        assert_eq!(pointed(text, &problems[0]), at, "{text}");
        assert!(problems[0].message().starts_with(message), "{text}: {}", problems[0].message());
    }
}

#[test]
fn every_effect_of_the_catalogue_is_read_by_its_kind() {
    for name in effects::NAMES {
        let empty = toml::de::ValueDeserializer::parse("{}").unwrap();
        let read = Effect::deserialize_kind(name, empty).expect(name);
        // No effect has a parameter with a default: an empty table misses one.
        assert!(read.unwrap_err().message().starts_with("missing field"), "{name}");
    }
    assert!(Effect::deserialize_kind("backlash_y", toml::de::ValueDeserializer::parse("{}").unwrap()).is_none());
}

#[test]
fn every_effect_is_of_time_exactly_when_it_has_a_term_of_time() {
    // `displacement_timed` pairs the terms of `at_time` with the effects `is_of_time` says
    // have one: each effect's two statements must agree, and the term must be its
    // displacement at that time.
    let s = Sample { velocity: Xz::new(600.0, -300.0), t_min: 7.5, cut_length_m: 2.0, ..sample(20.0, -50.0) };
    for kind in EffectKind::ALL {
        let effect = kind.fitted([0.002, 0.001], 30.0);
        assert_eq!(effect.at_time(s.t_min).is_some(), effect.is_of_time(), "{}", kind.name());
        if let Some(term) = effect.at_time(s.t_min) {
            assert_eq!(term, effect.displacement(&s), "{}", kind.name());
        }
        // An effect is written as its parameters alone: its name is `kind` in the file.
        let Ok(serde_json::Value::Object(fields)) = serde_json::to_value(&effect) else { panic!("{}", kind.name()) };
        assert!(!fields.is_empty() && !fields.contains_key("kind"), "{}", kind.name());
    }
}

#[test]
fn table_files_are_renamed_in_place() {
    let text = "# slides\n[[axis_table]]\naxis = \"x\"\nfile = \"x.csv\"   # beside the model\n\n\
                [[axis_table]]\naxis = \"z\"\nfile = 'z.csv'\n";
    let renamed = model_file::with_table_files(text, |file| Some(format!("../machines/{file}"))).unwrap();
    assert_eq!(
        renamed,
        "# slides\n[[axis_table]]\naxis = \"x\"\nfile = \"../machines/x.csv\"   # beside the model\n\n\
         [[axis_table]]\naxis = \"z\"\nfile = \"../machines/z.csv\"\n"
    );
}
