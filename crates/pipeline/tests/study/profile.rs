//! The lab profile (`lab.ron`, docs/PROFILE.md): a study that names it and its centrifuge
//! states only what is its own and runs to the same numbers as the study that states
//! everything; a value the study states overrides the profile, and the results say which came
//! from where; a bad profile is refused with every problem at once, each naming the profile
//! and its field; equipment past its calibration due date on the measurement date is warned.

use std::path::{Path, PathBuf};

use pipeline::{Inputs, PipelineError, Profile, StudyConfig, ValueSource};

use crate::{chain, root};

/// The fixture profile (fixtures/lab-folder/lab.ron).
fn lab() -> (Profile, PathBuf) {
    let path = root().join("fixtures/lab-folder/lab.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    (Profile::from_ron(&text, &path).unwrap(), path)
}

/// fixtures/studies/two_orientation.ron with what the profile states left out: the radius,
/// g, the lever, the radii of both mountings, the `uncertainty` section, the certificate's
/// laboratory, place, equipment, procedure, traceability, decision rule and authorisation.
/// The certificate's `deviations` and limits stay (the study's own).
fn two_orientation_with_profile(extra: &str, dates: &str) -> String {
    let reference =
        std::fs::read_to_string(root().join("fixtures/studies/two_orientation.ron")).unwrap();
    let phases = &reference[reference.find("    phases: [").unwrap()
        ..reference
            .find("    // The probe method's calibration")
            .unwrap()];
    format!(
        r#"(
    name: "two_orientation",
    profile: "../lab-folder/lab.ron",
    centrifuge: "ZF-2",
    k1_rad_s_g: 0.56,
{extra}{phases}    calibration: (
        table: (file: "../two_orientation/piga_ia_in.csv"),
        compensate_with: "spindle",
        k1: fitted,
        seed: 1,
    ),
    two_orientation: (
        orientations: [
            (orientation: ia_in, table: (file: "../two_orientation/piga_ia_in.csv")),
            (orientation: ia_out, table: (file: "../two_orientation/piga_ia_out.csv")),
        ],
        compare_with: "spindle",
        seed: 1,
    ),
    certificate: (
        id: "CC-2026-0057",
        customer: (name: "Example Guidance Systems Ltd", address: "4 Gyro Street, 56789 Sample City"),
        item: (
            description: "pendulous integrating gyroscopic accelerometer (PIGA)",
            manufacturer: "Example Instruments",
            model: "PIGA-16",
            serial: "SN 1604-0142",
            condition: "no visible damage; sealed; mounting surface clean",
        ),
        dates: {dates},
        operator: "A. Operator",
        conditions: [(quantity: "ambient temperature", value: "20.4 °C to 20.9 °C")],
        deviations: "none",
        limits: [(coefficient: k2, unit: micro, lower: -20.0, upper: 20.0)],
        authorisation: (name: "B. Manager"),
    ),
)"#
    )
}

const DATES: &str =
    r#"(received: "2026-12-01", measured: "2026-12-03 to 2026-12-04", issued: "2026-12-08")"#;

/// The study text's inputs with the fixture profile, as if the file lay in fixtures/studies/.
fn inputs(text: &str) -> Result<Inputs, PipelineError> {
    let path = root().join("fixtures/studies/two_orientation_profile.ron");
    let config = StudyConfig::from_ron(text, &path)?;
    let (profile, _) = lab();
    Inputs::with_profile(config, Some(&profile), &path, &pipeline::Files)
}

#[test]
fn a_study_naming_its_profile_runs_to_the_numbers_of_the_study_stating_everything() {
    let with_profile =
        pipeline::run(&inputs(&two_orientation_with_profile("", DATES)).unwrap()).unwrap();
    let reference = pipeline::run(
        &pipeline::load_study(&root().join("fixtures/studies/two_orientation.ron")).unwrap(),
    )
    .unwrap();
    assert_eq!(with_profile.inputs, reference.inputs);
    assert_eq!(with_profile.phases, reference.phases);
    // The same numbers; g's source is the profile's words.
    let mut calibration = with_profile.calibration.clone().unwrap();
    assert_eq!(
        calibration.g_source,
        "nominal 9.8 m/s², the value the simulation used (a laboratory states its gravity survey)"
    );
    calibration
        .g_source
        .clone_from(&reference.calibration.as_ref().unwrap().g_source);
    assert_eq!(Some(calibration), reference.calibration);
    assert_eq!(with_profile.two_orientation, reference.two_orientation);
    let cert = with_profile.certificate.as_ref().unwrap();
    let reference_cert = reference.certificate.as_ref().unwrap();
    // The laboratory as the reference states it, and its country (which the digital
    // certificate states) from the profile.
    let mut laboratory = cert.laboratory.clone();
    assert_eq!(laboratory.country.as_deref(), Some("DE"));
    laboratory.country = None;
    assert_eq!(laboratory, reference_cert.laboratory);
    assert_eq!(cert.location, reference_cert.location);
    assert_eq!(cert.procedure, reference_cert.procedure);
    assert_eq!(cert.authorisation, reference_cert.authorisation);
    // The same statements; where their limit comes from is the profile's `limits_source`
    // (the reference states its own for its limit).
    let source = "the customer's specification, as agreed at contract review";
    assert_eq!(
        cert.conformity
            .as_ref()
            .and_then(|c| c.limits_source.as_deref()),
        Some(source)
    );
    let mut statements = cert.conformity.as_ref().unwrap().statements.clone();
    for s in &mut statements {
        assert_eq!(s.source.as_deref(), Some(source), "{}", s.coefficient);
        s.source
            .clone_from(&reference_cert.conformity.as_ref().unwrap().statements[0].source);
    }
    assert_eq!(
        Some(&statements),
        reference_cert.conformity.as_ref().map(|c| &c.statements)
    );
    // Every Type B input with its standing statement, at the budget's standard uncertainty.
    for t in &reference_cert.traceability {
        let ours = cert
            .traceability
            .iter()
            .find(|x| x.input == t.input)
            .unwrap_or_else(|| panic!("no traceability of {}", t.input));
        assert_eq!(ours.u, t.u, "{}", t.input);
    }
    let roles: Vec<&str> = cert.equipment.iter().map(|e| e.role.as_str()).collect();
    assert_eq!(
        roles,
        [
            "precision centrifuge",
            "displacement probe",
            "data acquisition",
            "local gravity (survey)"
        ]
    );
    assert_eq!(cert.equipment[1].identity, "CP-7731");
    // Which value came from where.
    let used = with_profile.profile.as_ref().unwrap();
    assert_eq!(used.centrifuge, "ZF-2");
    assert_eq!(used.probe.as_deref(), Some("CP-7731"));
    let from = |field: &str| {
        used.values
            .iter()
            .find(|v| v.field == field)
            .unwrap_or_else(|| panic!("no origin for {field}: {:?}", used.values))
            .clone()
    };
    for field in [
        "radius_m",
        "g_m_s2",
        "lever.pivot_to_probe_mm",
        "lever.probe_direction",
        "lever.angle_zero_deg",
        "uncertainty.radius_u_m",
        "uncertainty.probe_gain_u_relative",
        "two_orientation.orientations[1].radius_m",
        "certificate.equipment",
        "certificate.laboratory",
    ] {
        assert_eq!(from(field).from, ValueSource::Profile, "{field}");
    }
    assert!(
        from("radius_m")
            .profile_field
            .ends_with("lab.ron: centrifuges[0].radius_m")
    );
    // The study names who signs; the profile gives the role.
    assert_eq!(
        from("certificate.authorisation.role").from,
        ValueSource::Profile
    );
    assert_eq!(
        from("certificate.traceability (probe_gain)").from,
        ValueSource::Profile
    );
    // The same warnings (the arm stretch the probe does not see), and no due date passed.
    assert_eq!(with_profile.warnings, reference.warnings);
}

#[test]
fn what_the_study_states_overrides_the_profile_and_says_so() {
    let text = two_orientation_with_profile(
        "    radius_m: 2.6,\n    lever: (probe_to_piga_mm: 500.0),\n    uncertainty: (radius_u_m: 1.0e-5),\n",
        DATES,
    );
    let study = inputs(&text);
    // An overridden uncertainty needs the study's own traceability statement.
    let e = study.unwrap_err();
    assert!(
        chain(&e).contains("certificate.traceability (input: radius)"),
        "{}",
        chain(&e)
    );
    let text = text.replace(
        "        deviations: \"none\",",
        "        deviations: \"none\",\n        traceability: [(input: radius, statement: \"re-measured for this job, report R-7\")],",
    );
    let results = pipeline::run(&inputs(&text).unwrap()).unwrap();
    assert_eq!(results.inputs.radius_m, 2.6);
    let used = results.profile.as_ref().unwrap();
    for (field, source) in [
        ("radius_m", ValueSource::Study),
        ("lever.probe_to_piga_mm", ValueSource::Study),
        ("lever.pivot_to_probe_mm", ValueSource::Profile),
        ("uncertainty.radius_u_m", ValueSource::Study),
        ("uncertainty.g_u_m_s2", ValueSource::Profile),
    ] {
        let v = used.values.iter().find(|v| v.field == field).unwrap();
        assert_eq!(v.from, source, "{field}");
    }
    let cert = results.certificate.as_ref().unwrap();
    let radius = cert
        .traceability
        .iter()
        .find(|t| t.input == "R (working radius)")
        .unwrap();
    assert_eq!(radius.statement, "re-measured for this job, report R-7");
    assert_eq!(radius.u, Some(1.0e-5));
}

/// The probe direction and the angle zero are the centrifuge's in the profile; the study's
/// override them (either name of a direction), and neither stated leaves the angle zero
/// unstated (0 taken, and said) and the direction the paper's.
#[test]
fn the_centrifuges_probe_direction_and_angle_zero_come_from_the_profile_unless_the_study_states_them()
 {
    let (profile, path) = lab();
    let study = root().join("fixtures/studies/two_orientation_profile.ron");
    let text = two_orientation_with_profile(
        "    lever: (angle_zero_deg: 30.0, probe_direction: reading_rises_towards_piga),\n",
        DATES,
    );
    let mut config = StudyConfig::from_ron(&text, &study).unwrap();
    let used = profile.apply(&mut config, &study).unwrap();
    assert_eq!(config.lever.angle_zero_deg, Some(30.0));
    assert_eq!(
        config.lever.probe_direction,
        Some(pipeline::ProbeDirectionName::AlongO1X1)
    );
    for field in ["lever.angle_zero_deg", "lever.probe_direction"] {
        let v = used.values.iter().find(|v| v.field == field).unwrap();
        assert_eq!(v.from, ValueSource::Study, "{field}");
    }
    // The profile's, when the study states neither.
    let mut config =
        StudyConfig::from_ron(&two_orientation_with_profile("", DATES), &study).unwrap();
    profile.apply(&mut config, &study).unwrap();
    assert_eq!(config.lever.angle_zero_deg, Some(0.0));
    assert_eq!(
        config.lever.probe_direction,
        Some(pipeline::ProbeDirectionName::AgainstO1X1)
    );
    // A profile whose centrifuge states no angle zero: none is stated, and the results say
    // 0 was taken.
    let lab_text = std::fs::read_to_string(&path).unwrap();
    let without = lab_text.replacen("                angle_zero_deg: 0.0,\n", "", 1);
    assert_ne!(without, lab_text);
    let profile = Profile::from_ron(&without, &path).unwrap();
    let config = StudyConfig::from_ron(&two_orientation_with_profile("", DATES), &study).unwrap();
    let results = pipeline::run(
        &Inputs::with_profile(config, Some(&profile), &study, &pipeline::Files).unwrap(),
    )
    .unwrap();
    assert!(!results.inputs.angle_zero.stated);
    assert!(
        !results
            .profile
            .as_ref()
            .unwrap()
            .values
            .iter()
            .any(|v| v.field == "lever.angle_zero_deg")
    );
}

#[test]
fn equipment_past_its_calibration_due_date_is_warned() {
    let late = r#"(received: "2027-02-01", measured: "2027-02-03", issued: "2027-02-08")"#;
    let study = inputs(&two_orientation_with_profile("", late)).unwrap();
    let warnings = study.warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_eq!(warnings[0].code, "calibration_overdue");
    assert!(
        warnings[0].message.contains("displacement probe CP-7731")
            && warnings[0].message.contains("2027-01-15"),
        "{}",
        warnings[0].message
    );
    // A measurement date that cannot be compared says so.
    let vague =
        r#"(received: "2026-12-01", measured: "early December 2026", issued: "2026-12-08")"#;
    let warnings = inputs(&two_orientation_with_profile("", vague))
        .unwrap()
        .warnings();
    assert_eq!(warnings.len(), 1);
    assert_eq!(warnings[0].code, "calibration_due_unchecked");
    assert!(warnings[0].message.contains("early December 2026"));
}

/// The fixture profile's text with `from` replaced by `to`.
fn broken(replacements: &[(&str, &str)]) -> PipelineError {
    let (_, path) = lab();
    let mut text = std::fs::read_to_string(&path).unwrap();
    for (from, to) in replacements {
        assert!(text.contains(from), "{from}");
        text = text.replacen(from, to, 1);
    }
    let profile = Profile::from_ron(&text, Path::new("lab.ron")).unwrap();
    profile.validate().unwrap_err()
}

#[test]
fn a_bad_profile_is_refused_with_every_problem_naming_lab_ron_and_the_field() {
    let e = broken(&[
        ("radius_m: 2.5,", "radius_m: -2.5,"),
        (
            "calibration_due: \"2027-01-15\"",
            "calibration_due: \"15.01.2027\"",
        ),
        ("probe: \"CP-7731\",", "probe: \"CP-9999\","),
        (
            "        (name: \"C. Deputy\", role: \"deputy head of the inertial laboratory\"),",
            "        (name: \"B. Manager\", role: \"\"),",
        ),
        ("                probe_direction: against_o1_x1,\n", ""),
        ("rate_scale: \"spindle encoder", "rate_scale: \" \", // \""),
        ("u_m_s2: 1.0e-5,", "u_m_s2: 9.8,"),
        (
            "identity: \"asset 1021\"",
            "identity: \"asset \u{202e}1201\"",
        ),
        ("country: \"DE\"", "country: \"Germany\""),
    ]);
    let text = chain(&e);
    let PipelineError::Several { errors } = &e else {
        panic!("every problem at once: {text}");
    };
    for line in errors.iter().map(ToString::to_string) {
        assert!(line.starts_with("lab.ron: field `"), "{line}");
    }
    for expected in [
        "`centrifuges[0].radius_m` = -2.5: must be finite and > 0",
        "`probes[0].calibration_due` = \"15.01.2027\": not a date written YYYY-MM-DD (hint: write it as YYYY-MM-DD (ISO 8601): \"2027-01-15\")",
        "`centrifuges[0].probe`: `CP-9999` is not one of CP-7731",
        "`signatories[1].role` is required",
        "`signatories[1].name`: the name `B. Manager` is already used at `signatories[0].name`",
        "`centrifuges[0].lever.probe_direction` is required: which way the probe measures",
        "`centrifuges[0].traceability.rate_scale` is required",
        "`centrifuges[0].identity` holds the character U+202E",
        "`gravity.u_m_s2` = 9.8: a standard uncertainty as large as the quantity itself (`gravity.g_m_s2` = 9.8 m/s²)",
        "`laboratory.country`: must be a country code of ISO 3166-1: two capital letters",
    ] {
        assert!(text.contains(expected), "{expected}\nin\n{text}");
    }
    assert_eq!(errors.len(), 10, "{text}");
}

#[test]
fn a_profile_is_parsed_with_located_errors_in_its_own_words() {
    let e = Profile::from_ron("(\n    laboratory: (nmae: \"x\"),\n)", Path::new("lab.ron"))
        .unwrap_err();
    let text = e.to_string();
    assert!(
        text.starts_with("lab.ron:2:") && text.contains("unknown field `nmae` in `laboratory`"),
        "{text}"
    );
}

#[test]
fn a_study_is_refused_a_centrifuge_or_signatory_the_profile_does_not_have() {
    let text = two_orientation_with_profile("", DATES)
        .replace("centrifuge: \"ZF-2\"", "centrifuge: \"ZF-9\"");
    let e = chain(&inputs(&text).unwrap_err());
    assert!(
        e.contains("field `centrifuge`: `ZF-9` is not one of ZF-2"),
        "{e}"
    );
    let text = two_orientation_with_profile("", DATES).replace(
        "authorisation: (name: \"B. Manager\")",
        "authorisation: (name: \"Z. Nobody\")",
    );
    let e = chain(&inputs(&text).unwrap_err());
    assert!(
        e.contains(
            "`certificate.authorisation.name`: `Z. Nobody` is not one of B. Manager, C. Deputy"
        ),
        "{e}"
    );
    // Two signatories and none named: the study must say who signs.
    let text = two_orientation_with_profile("", DATES)
        .replace("        authorisation: (name: \"B. Manager\"),\n", "");
    let e = chain(&inputs(&text).unwrap_err());
    assert!(
        e.contains(
            "`certificate.authorisation.name` is required: who authorises the certificate: one of"
        ),
        "{e}"
    );
    // A study naming a profile, built without it, says how to read it.
    let path = root().join("fixtures/studies/x.ron");
    let config = StudyConfig::from_ron(&two_orientation_with_profile("", DATES), &path).unwrap();
    let e = Inputs::new(config, &path, &pipeline::Files).unwrap_err();
    assert!(matches!(e, PipelineError::ProfileNotRead { .. }), "{e}");
    // Without a profile, the radius is required, and the error says where else it can come from.
    let text = two_orientation_with_profile("", DATES).replace(
        "    profile: \"../lab-folder/lab.ron\",\n    centrifuge: \"ZF-2\",\n",
        "",
    );
    let config = StudyConfig::from_ron(&text, &path).unwrap();
    let e = chain(&Inputs::new(config, &path, &pipeline::Files).unwrap_err());
    assert!(
        e.contains("field `radius_m` is required") && e.contains("profile: \"lab.ron\""),
        "{e}"
    );
}

#[test]
fn load_study_reads_the_profile_the_study_names_and_records_its_digest() {
    let scratch = test_support::Scratch::new("pipeline-profile-load");
    let lab_path = root().join("fixtures/lab-folder/lab.ron");
    std::fs::copy(&lab_path, scratch.0.join("lab.ron")).unwrap();
    let text = r#"(name: "x", profile: "lab.ron", centrifuge: "ZF-2", k1_rad_s_g: 0.56,
        phases: [(name: "p", points: radius_error([
            (rate_deg_s: 10.0, radius_error_um: 1.0),
            (rate_deg_s: 100.0, radius_error_um: 0.9),
            (rate_deg_s: 200.0, radius_error_um: 0.6)]))])"#;
    let study = scratch.0.join("study.ron");
    std::fs::write(&study, text).unwrap();
    let inputs = pipeline::load_study(&study).unwrap();
    let (path, digest) = inputs.profile_file().unwrap();
    assert_eq!(path, scratch.0.join("lab.ron"));
    let bytes = std::fs::read(&lab_path).unwrap();
    assert_eq!(digest.unwrap(), &pipeline::FileDigest::of(&bytes));
    let results = pipeline::run(&inputs).unwrap();
    assert_eq!(results.inputs.radius_m, 2.5);
    assert_eq!(results.inputs.g_m_s2, 9.8);
    // A profile that is not there is named.
    std::fs::remove_file(scratch.0.join("lab.ron")).unwrap();
    let e = chain(&pipeline::load_study(&study).unwrap_err());
    assert!(e.contains("lab.ron"), "{e}");
}
