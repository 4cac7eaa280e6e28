//! Every invalid input, model failure and non-convergence is a typed error naming what is at
//! fault; failed trials within the allowance are counted and reported.

use uncertainty::{
    Distribution, Dof, Evaluation, GumOptions, InputQuantity, Inputs, McOptions, ModelError,
    Trials, UncertaintyError, gum, model_fn, monte_carlo,
};

fn err(quantities: Vec<InputQuantity>) -> UncertaintyError {
    Inputs::new(quantities).unwrap_err()
}

#[test]
fn invalid_input_quantities() {
    let ok = || InputQuantity::normal("x", 1.0, 0.1);
    let with = |f: fn(&mut InputQuantity)| {
        let mut q = ok();
        f(&mut q);
        vec![q]
    };
    assert_eq!(err(vec![]), UncertaintyError::NoInputs);
    assert!(matches!(
        err(with(|q| q.standard_uncertainty = -0.1)),
        UncertaintyError::InvalidStandardUncertainty { input, .. } if input == "x"
    ));
    assert!(matches!(
        err(with(|q| q.standard_uncertainty = f64::NAN)),
        UncertaintyError::InvalidStandardUncertainty { input, .. } if input == "x"
    ));
    assert!(matches!(
        err(with(|q| q.standard_uncertainty = f64::INFINITY)),
        UncertaintyError::InvalidStandardUncertainty { .. }
    ));
    assert!(matches!(
        err(with(|q| q.value = f64::NAN)),
        UncertaintyError::NonFiniteValue { input, .. } if input == "x"
    ));
    assert!(matches!(
        err(with(|q| q.dof = Dof::Finite(0.0))),
        UncertaintyError::InvalidDof { input, dof } if input == "x" && dof == 0.0
    ));
    assert!(matches!(
        err(with(|q| q.dof = Dof::Finite(f64::INFINITY))),
        UncertaintyError::InvalidDof { .. }
    ));
    assert!(matches!(
        err(with(|q| q.distribution = Distribution::StudentT)),
        UncertaintyError::StudentTNeedsFiniteDof { input } if input == "x"
    ));
    // Type A with finite ν must be drawn from the t distribution (JCGM 101 §6.4.9).
    assert!(matches!(
        err(with(|q| {
            q.kind = Evaluation::TypeA;
            q.dof = Dof::Finite(5.0);
        })),
        UncertaintyError::TypeADistribution { input, distribution: Distribution::Normal, .. } if input == "x"
    ));
    assert!(matches!(
        err(with(|q| q.name.clear())),
        UncertaintyError::EmptyName { index: 0 }
    ));
    assert_eq!(
        err(vec![ok(), ok()]),
        UncertaintyError::DuplicateName { name: "x".into() }
    );
}

#[test]
fn invalid_correlation_matrices() {
    let two = || {
        vec![
            InputQuantity::normal("a", 1.0, 0.1),
            InputQuantity::normal("b", 1.0, 0.1),
        ]
    };
    assert_eq!(
        Inputs::with_correlation(two(), &[1.0, 0.0, 0.0]).unwrap_err(),
        UncertaintyError::CorrelationSize {
            inputs: 2,
            got: 3,
            expected: 4
        }
    );
    assert!(matches!(
        Inputs::with_correlation(two(), &[1.0, 0.5, 0.4, 1.0]).unwrap_err(),
        UncertaintyError::InvalidCorrelation { first, second, .. } if first == "b" && second == "a"
    ));
    assert!(matches!(
        Inputs::with_correlation(two(), &[1.0, 1.5, 1.5, 1.0]).unwrap_err(),
        UncertaintyError::InvalidCorrelation { value, .. } if value == 1.5
    ));
    assert!(matches!(
        Inputs::with_correlation(two(), &[0.9, 0.0, 0.0, 1.0]).unwrap_err(),
        UncertaintyError::InvalidCorrelation { .. }
    ));
    let three = vec![
        InputQuantity::normal("a", 1.0, 0.1),
        InputQuantity::normal("b", 1.0, 0.1),
        InputQuantity::normal("c", 1.0, 0.1),
    ];
    let indefinite = [1.0, 0.9, 0.9, 0.9, 1.0, -0.9, 0.9, -0.9, 1.0];
    assert_eq!(
        Inputs::with_correlation(three, &indefinite).unwrap_err(),
        UncertaintyError::CorrelationNotPositiveSemiDefinite { input: "c".into() }
    );
    let mixed = vec![
        InputQuantity::type_a("a", 1.0, 0.1, Dof::Finite(4.0)),
        InputQuantity::normal("b", 1.0, 0.1),
    ];
    assert!(matches!(
        Inputs::with_correlation(mixed, &[1.0, 0.5, 0.5, 1.0]).unwrap_err(),
        UncertaintyError::CorrelatedDofMismatch { first, second, .. } if first == "a" && second == "b"
    ));
    // The Monte Carlo method draws correlated inputs from a multivariate normal or t only.
    let rect = Inputs::with_correlation(
        vec![
            InputQuantity::normal("a", 1.0, 0.1),
            InputQuantity::rectangular("b", 1.0, 0.1),
        ],
        &[1.0, 0.5, 0.5, 1.0],
    )
    .unwrap();
    let model = model_fn(["y"], |x, y| {
        y[0] = x[0] + x[1];
        Ok(())
    });
    assert!(gum(&model, &rect, &GumOptions::default()).is_ok());
    assert!(matches!(
        monte_carlo(&model, &rect, &McOptions::default()).unwrap_err(),
        UncertaintyError::CorrelatedDistribution { input, distribution: Distribution::Rectangular } if input == "b"
    ));
}

#[test]
fn model_failures_at_the_estimate_and_while_differentiating() {
    let inputs = Inputs::new(vec![InputQuantity::normal("x", 0.0, 0.1)]).unwrap();
    let inverse = model_fn(["inv"], |x, y| {
        y[0] = 1.0 / x[0];
        Ok(())
    });
    assert!(matches!(
        gum(&inverse, &inputs, &GumOptions::default()).unwrap_err(),
        UncertaintyError::NonFiniteEstimate { output, .. } if output == "inv"
    ));
    let singular = model_fn(["s"], |_, _| Err(ModelError::Singular));
    assert_eq!(
        gum(&singular, &inputs, &GumOptions::default()).unwrap_err(),
        UncertaintyError::ModelFailedAtEstimate {
            source: ModelError::Singular
        }
    );
    // √x at x = 0.0005 with u = 0.1: the differentiation steps reach x < 0.
    let inputs = Inputs::new(vec![InputQuantity::normal("x", 0.0005, 0.1)]).unwrap();
    let root = model_fn(["root"], |x, y| {
        if x[0] < 0.0 {
            return Err(ModelError::OutOfDomain { index: 0 });
        }
        y[0] = x[0].sqrt();
        Ok(())
    });
    assert_eq!(
        gum(&root, &inputs, &GumOptions::default()).unwrap_err(),
        UncertaintyError::SensitivityFailed {
            input: "x".into(),
            source: ModelError::OutOfDomain { index: 0 }
        }
    );
    let inputs = Inputs::new(vec![InputQuantity::normal("x", 1.0, 0.1)]).unwrap();
    assert_eq!(
        gum(&root.with_input_count(2), &inputs, &GumOptions::default()).unwrap_err(),
        UncertaintyError::InputCount { model: 2, given: 1 }
    );
}

#[test]
fn failed_trials_are_counted_and_too_many_are_an_error() {
    // √x with x ~ N(4, 1): x < 0 in Φ(−4) = 3.2e-5 of the trials, within the default 1e-3.
    let root = model_fn(["root"], |x, y| {
        if x[0] < 0.0 {
            return Err(ModelError::OutOfDomain { index: 0 });
        }
        y[0] = x[0].sqrt();
        Ok(())
    });
    let inputs = Inputs::new(vec![InputQuantity::normal("x", 4.0, 1.0)]).unwrap();
    let mc = monte_carlo(&root, &inputs, &McOptions::default()).unwrap();
    assert!(mc.failed_trials > 0, "{} trials", mc.trials);
    assert!((mc.failed_trials as f64) < 1e-4 * mc.trials as f64);
    assert_eq!(mc.first_failure, Some(ModelError::OutOfDomain { index: 0 }));
    assert!(mc.outputs[0].estimate.is_finite());

    // x ~ N(2, 1): Φ(−2) = 2.3 % of the trials fail.
    let inputs = Inputs::new(vec![InputQuantity::normal("x", 2.0, 1.0)]).unwrap();
    let e = monte_carlo(&root, &inputs, &McOptions::default()).unwrap_err();
    let UncertaintyError::TooManyFailedTrials {
        failed,
        trials,
        first,
        ..
    } = e
    else {
        panic!("{e:?}")
    };
    assert_eq!(first, ModelError::OutOfDomain { index: 0 });
    assert!(
        (failed as f64 / trials as f64 - 0.0228).abs() < 0.005,
        "{failed}/{trials}"
    );

    // A non-finite output at a draw is a failed trial too (here NaN above 3.5σ: 2.3e-4).
    let nan = model_fn(["nan"], |x, y| {
        y[0] = if x[0] > 3.5 { f64::NAN } else { x[0] };
        Ok(())
    });
    let inputs = Inputs::new(vec![InputQuantity::normal("x", 0.0, 1.0)]).unwrap();
    let mc = monte_carlo(&nan, &inputs, &McOptions::default()).unwrap();
    assert!(mc.failed_trials > 0);
    assert!(mc.outputs[0].coverage_interval.1 < 3.5);
}

#[test]
fn not_converged_within_the_cap_names_the_output() {
    // Four significant digits of u take far more than three batches of 10⁴ trials; the
    // output with the wider spread is the first to miss.
    let inputs = Inputs::new(vec![
        InputQuantity::normal("a", 1.0, 0.1),
        InputQuantity::rectangular("b", 0.0, 1.0),
    ])
    .unwrap();
    let model = model_fn(["steady", "wide"], |x, y| {
        y[0] = 1.0;
        y[1] = x[0] + x[1];
        Ok(())
    });
    let options = McOptions {
        n_dig: 4,
        trials: Trials::Adaptive { max_trials: 30_000 },
        ..McOptions::default()
    };
    let e = monte_carlo(&model, &inputs, &options).unwrap_err();
    assert!(
        matches!(
            &e,
            UncertaintyError::NotConverged { output, trials: 30_000, max_trials: 30_000, .. }
                if output == "wide"
        ),
        "{e:?}"
    );
}

#[test]
fn a_cauchy_output_settles_on_its_interval_and_is_marked() {
    // t with ν = 1 (Cauchy) has neither mean nor variance: the adaptive procedure waits on
    // the coverage limits only (it used to run to the cap) and marks the output.
    let inputs = Inputs::new(vec![
        InputQuantity::normal("a", 1.0, 0.1),
        InputQuantity::type_a("b", 0.0, 1.0, Dof::Finite(1.0)),
    ])
    .unwrap();
    let model = model_fn(["steady", "heavy"], |x, y| {
        y[0] = x[0];
        y[1] = x[1];
        Ok(())
    });
    let mc = monte_carlo(&model, &inputs, &McOptions::default()).unwrap();
    let heavy = mc.output("heavy").unwrap();
    assert!(heavy.heavy_tailed);
    // The Cauchy's 95 % interval is ±12.706.
    assert!(
        (heavy.coverage_interval.1 - 12.706).abs() < 0.3,
        "{:?}",
        heavy.coverage_interval
    );
}

#[test]
fn invalid_options() {
    let inputs = Inputs::new(vec![InputQuantity::normal("x", 1.0, 0.1)]).unwrap();
    let model = model_fn(["y"], |x, y| {
        y[0] = x[0];
        Ok(())
    });
    for (options, name) in [
        (
            McOptions {
                coverage_probability: 1.0,
                ..McOptions::default()
            },
            "coverage_probability",
        ),
        (
            McOptions {
                coverage_probability: 0.99999,
                ..McOptions::default()
            },
            "coverage_probability",
        ),
        (
            McOptions {
                max_failed_fraction: 0.6,
                ..McOptions::default()
            },
            "max_failed_fraction",
        ),
        (
            McOptions {
                n_dig: 0,
                ..McOptions::default()
            },
            "n_dig",
        ),
        (
            McOptions {
                trials: Trials::Adaptive { max_trials: 15_000 },
                ..McOptions::default()
            },
            "max_trials",
        ),
        (
            McOptions {
                trials: Trials::Fixed(100),
                ..McOptions::default()
            },
            "trials",
        ),
        // beyond the cap: TooManyTrials, with its memory and time
        // (too_many_trials_are_refused_before_any_is_drawn)
    ] {
        assert!(
            matches!(monte_carlo(&model, &inputs, &options), Err(UncertaintyError::InvalidOption { name: n, .. }) if n == name),
            "{name}"
        );
    }
    let gum_options = GumOptions {
        coverage_probability: 0.0,
        ..GumOptions::default()
    };
    assert!(matches!(
        gum(&model, &inputs, &gum_options),
        Err(UncertaintyError::InvalidOption {
            name: "coverage_probability",
            ..
        })
    ));
    let none = model_fn(Vec::<String>::new(), |_, _| Ok(()));
    assert_eq!(
        gum(&none, &inputs, &GumOptions::default()).unwrap_err(),
        UncertaintyError::NoOutputs
    );
}

#[test]
fn too_many_trials_are_refused_before_any_is_drawn() {
    // Issue 32: 10⁹ fixed trials aborted the process on an 8 GB allocation. The model counts
    // its evaluations: none may run.
    let calls = std::sync::atomic::AtomicUsize::new(0);
    let inputs = Inputs::new(vec![InputQuantity::normal("a", 1.0, 0.1)]).unwrap();
    let model = model_fn(["y", "z"], |x, y| {
        calls.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        y[0] = x[0];
        y[1] = 2.0 * x[0];
        Ok(())
    });
    for trials in [
        Trials::Fixed(1_000_000_000),
        Trials::Fixed(uncertainty::MAX_TRIALS + 1),
        Trials::Adaptive {
            max_trials: u64::MAX,
        },
    ] {
        let options = McOptions {
            trials,
            ..McOptions::default()
        };
        let e = monte_carlo(&model, &inputs, &options).unwrap_err();
        match &e {
            UncertaintyError::TooManyTrials { max, bytes, .. } => {
                assert_eq!(*max, uncertainty::MAX_TRIALS);
                assert!(*bytes > 2 * 8 * uncertainty::MAX_TRIALS, "{bytes}");
            }
            other => panic!("{other:?}"),
        }
        let text = e.to_string();
        assert!(
            text.contains("at most 10000000 Monte Carlo trials"),
            "{text}"
        );
        // Short numbers: no 20-digit expansion of the bytes or the trials.
        assert!(text.len() < 300, "{text}");
    }
    assert_eq!(calls.load(std::sync::atomic::Ordering::Relaxed), 0);
    // The check the study and the Python package call, with the same words.
    let e = uncertainty::check_trials(1_000_000_000, 6).unwrap_err();
    assert_eq!(
        e.to_string(),
        "trials = 1000000000: at most 10000000 Monte Carlo trials are drawn; 1000000000 would \
         keep 48000000000 bytes (44.7 GiB) of model values (8 bytes per trial and output) and \
         take about 100 s of CPU"
    );
    assert!(uncertainty::check_trials(uncertainty::MAX_TRIALS, 6).is_ok());
}
