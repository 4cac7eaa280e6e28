//! A unit's symbol is the word a configuration writes for it (what `check` repeats to the
//! person who wrote it).

use recording::{AngleUnit, LengthUnit, TimeUnit};

#[test]
fn each_units_symbol_is_its_configuration_word() {
    for unit in [TimeUnit::S, TimeUnit::Ms, TimeUnit::Us, TimeUnit::Ns] {
        assert_eq!(ron::to_string(&unit).unwrap(), unit.symbol());
    }
    for unit in [
        LengthUnit::Nm,
        LengthUnit::Um,
        LengthUnit::Mm,
        LengthUnit::M,
    ] {
        assert_eq!(ron::to_string(&unit).unwrap(), unit.symbol());
    }
    for unit in [
        AngleUnit::Deg,
        AngleUnit::Rad,
        AngleUnit::Counts { per_rev: 4096 },
    ] {
        let written = ron::to_string(&unit).unwrap();
        assert!(
            written.starts_with(unit.symbol()),
            "{written} {}",
            unit.symbol()
        );
    }
    assert_eq!(
        ron::from_str::<AngleUnit>("counts(per_rev: 4096)").unwrap(),
        AngleUnit::Counts { per_rev: 4096 }
    );
}
