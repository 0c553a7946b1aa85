// The ages of a series: a scale in their unit, and the fractional step of any age between
// them (linear between steps). The ages are what export recorded in the materials' extras
// (patina-texgen view passes them as `recorded`, in `recordedUnit`); a glTF series made
// elsewhere has only its variant names, read as numbers with a unit ("0 y", "12 h") when
// they are, else as steps.
const UNIT = /^\s*([-+0-9.eE]+)\s*(\S*)/;

export function ageScale(names, recorded = [], recordedUnit = '') {
  const parsed = names.map((n) => UNIT.exec(n));
  const fromExtras = recorded.length === names.length && recorded.every(Number.isFinite);
  const numeric = fromExtras || parsed.every((m) => m && Number.isFinite(Number(m[1])));
  const values = fromExtras ? recorded
    : numeric ? parsed.map((m) => Number(m[1])) : names.map((_, i) => i);
  const unit = fromExtras ? recordedUnit : numeric ? parsed[0][2] : '';
  const ascending = values.every((v, i) => i === 0 || v > values[i - 1]);
  const ages = ascending ? values : names.map((_, i) => i);
  return {
    first: ages[0],
    last: ages[ages.length - 1],
    /// The step position of `age`: i + the fraction between step i and i + 1.
    stepOf(age) {
      if (ages.length < 2 || age <= ages[0]) return 0;
      for (let i = 1; i < ages.length; ++i)
        if (age <= ages[i]) return i - 1 + (age - ages[i - 1]) / (ages[i] - ages[i - 1]);
      return ages.length - 1;
    },
    label(age) {
      return ascending && numeric ? `${Number(age.toFixed(2))} ${unit}`.trim() : names[Math.round(this.stepOf(age))];
    },
  };
}
