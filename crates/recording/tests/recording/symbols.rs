//! A unit's key is the word a configuration writes for it; its symbol is what a person reads
//! (µm and µs where the configuration writes `um` and `us`).

use recording::{AngleUnit, LengthUnit, TimeUnit};

#[test]
fn each_units_key_is_its_configuration_word() {
    for unit in [TimeUnit::S, TimeUnit::Ms, TimeUnit::Us, TimeUnit::Ns] {
        assert_eq!(ron::to_string(&unit).unwrap(), unit.key());
    }
    for unit in [
        LengthUnit::Nm,
        LengthUnit::Um,
        LengthUnit::Mm,
        LengthUnit::M,
    ] {
        assert_eq!(ron::to_string(&unit).unwrap(), unit.key());
    }
    for unit in [
        AngleUnit::Deg,
        AngleUnit::Rad,
        AngleUnit::Counts { per_rev: 4096 },
    ] {
        let written = ron::to_string(&unit).unwrap();
        assert!(written.starts_with(unit.key()), "{written} {}", unit.key());
    }
    assert_eq!(
        ron::from_str::<AngleUnit>("counts(per_rev: 4096)").unwrap(),
        AngleUnit::Counts { per_rev: 4096 }
    );
}

#[test]
fn each_units_symbol_is_what_a_person_reads() {
    let times: Vec<&str> = [TimeUnit::S, TimeUnit::Ms, TimeUnit::Us, TimeUnit::Ns]
        .map(TimeUnit::symbol)
        .to_vec();
    assert_eq!(times, ["s", "ms", "µs", "ns"]);
    let lengths: Vec<&str> = [
        LengthUnit::Nm,
        LengthUnit::Um,
        LengthUnit::Mm,
        LengthUnit::M,
    ]
    .map(LengthUnit::symbol)
    .to_vec();
    assert_eq!(lengths, ["nm", "µm", "mm", "m"]);
    // the gap unit's display (a probe's diagnostics, `check`) spells micrometres the same way
    assert_eq!(recording::GapUnit::Um.to_string(), LengthUnit::Um.symbol());
    assert_eq!(AngleUnit::Deg.symbol(), "deg");
}
