"""Results.to_pandas(): the recorded rows as a pandas DataFrame (docs/python.md,
"Results as pandas").  pandas is imported only here, when called: the rest of
the module needs NumPy only."""


def to_pandas(self, multiindex=False):
    """The recorded rows as a pandas DataFrame indexed by time ``t`` [s].

    One column per recorded scalar column, named like ``res.columns``
    (the flat names of the CSV and ``res.column()``: a vector quantity is
    split into ``<name>_x/_y/_z``, a quaternion into ``q_BN_0..3``, one
    column per wheel ``..._rpm_<i>``); these names are unique in a run.
    ``df.attrs["units"]``: column -> unit (and ``"t"``: ``"s"``); ``df.attrs["quantities"]``:
    column -> ``"group/quantity"`` (the message that recorded it, as
    ``res["group/quantity"]`` takes it); ``df.attrs["frames"]``: column ->
    frame.

    ``multiindex=True``: the columns are a MultiIndex of
    (quantity as "group/quantity", column, unit) instead of the flat names
    (``df["truth/omega_BN_B"]`` is then that quantity's three columns).
    """
    try:
        import pandas as pd
    except ImportError as e:  # the optional dependency (extra "pandas")
        raise ImportError("Results.to_pandas() needs pandas (Debian python3-pandas, or "
                          "pip install 'kestrel[pandas]')") from e
    columns = list(self.columns)
    units = self.units
    where = {}  # column -> (group/quantity, frame)
    for key, (_unit, frame, cols) in self.quantities.items():
        for c in cols:
            where[c] = (key, frame)
    if len(set(columns)) != len(columns):  # the harness's flat names are unique; guard anyway
        raise ValueError("to_pandas(): recorded column names are not unique")
    data = self.data
    if columns and columns[0] == "t":
        index = pd.Index(data[:, 0], name="t")
        data, columns = data[:, 1:], columns[1:]
    else:
        index = pd.RangeIndex(data.shape[0], name="row")
    if multiindex:
        cols = pd.MultiIndex.from_tuples([(where[c][0], c, units[c]) for c in columns],
                                         names=["quantity", "column", "unit"])
    else:
        cols = pd.Index(columns, name="column")
    df = pd.DataFrame(data.copy(), index=index, columns=cols)
    df.attrs["units"] = {df.index.name: units.get("t", "") if df.index.name == "t" else ""}
    df.attrs["units"].update({c: units[c] for c in columns})
    df.attrs["quantities"] = {c: where[c][0] for c in columns}
    df.attrs["frames"] = {c: where[c][1] for c in columns}
    return df
