//! CSV records written by the `csv` crate (RFC 4180): a field holding a comma, a quote or a
//! line break is quoted and its quotes doubled, so a column named `P,Q` stays one field;
//! other fields are written as they are, so ordinary names give the bytes they always gave.
//! Only headers and names go through here: numbers never need quoting and are written
//! directly, which keeps the streaming path as fast as it was.

/// One CSV record ending in `\n`, each field quoted only where it must be.
///
/// ```
/// use mechdiff::stream::record::csv_record;
///
/// assert_eq!(csv_record(["phi [deg]", "P,Q x [m]"]), "phi [deg],\"P,Q x [m]\"\n");
/// assert_eq!(csv_record(["say \"hi\""]), "\"say \"\"hi\"\"\"\n");
/// ```
pub fn csv_record<I>(fields: I) -> String
where
    I: IntoIterator,
    I::Item: AsRef<str>,
{
    write(fields, csv::QuoteStyle::Necessary)
}

/// One field in quotes, its quotes doubled (for a column that has always been quoted).
///
/// ```
/// use mechdiff::stream::record::csv_quoted;
///
/// assert_eq!(csv_quoted("dual (Dual2)"), "\"dual (Dual2)\"");
/// assert_eq!(csv_quoted("a\"b"), "\"a\"\"b\"");
/// ```
pub fn csv_quoted(field: &str) -> String {
    let mut line = write([field], csv::QuoteStyle::Always);
    line.pop();
    line
}

fn write<I>(fields: I, style: csv::QuoteStyle) -> String
where
    I: IntoIterator,
    I::Item: AsRef<str>,
{
    let mut writer = csv::WriterBuilder::new()
        .terminator(csv::Terminator::Any(b'\n'))
        .quote_style(style)
        .from_writer(Vec::new());
    // Writing to memory fails only on a record of another length than the first, and this
    // writer writes one record.
    for field in fields {
        writer
            .write_field(field.as_ref())
            .expect("a CSV field written to memory");
    }
    writer
        .write_record(None::<&[u8]>)
        .expect("one CSV record written to memory");
    let bytes = writer.into_inner().expect("a CSV record flushed to memory");
    String::from_utf8(bytes).expect("fields given as UTF-8 stay UTF-8")
}
