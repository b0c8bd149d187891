"""Storage of a sweep's rows: chunk files in ``OUTPUT.parts/`` written as cases finish,
merged into OUTPUT (Parquet or CSV) at the end; the rows already on disk let a rerun
skip the cases done."""

from __future__ import annotations

import os
import shutil
import time
import uuid
from collections.abc import Sequence
from pathlib import Path

from ..errors import InputError
from ..io.paths import output_path


class _Store:
    """Rows on disk: chunk files in ``OUTPUT.parts/``, merged into OUTPUT at the end."""

    def __init__(self, path: str | os.PathLike | None):
        self.path = Path(path) if path is not None else None
        if self.path is not None:
            ext = self.path.suffix.lower()
            if ext not in (".parquet", ".csv"):
                raise InputError(f"output must end in .parquet or .csv, got {ext or 'none'!r}",
                                 str(self.path))
            self.ext = ext
            output_path(self.path, option="output")  # its folder exists: none is created
            self.parts = self.path.with_name(self.path.name + ".parts")
        self.memory: list[dict] = []

    def _read(self, p: Path):
        """One results file of this study's kind; an InputError naming it where it is none
        (a parquet file cut short, text that is no table: a traceback from pyarrow) or has
        no case_id column (an empty one included: it was overwritten without a word)."""
        import pandas as pd

        try:
            df = pd.read_parquet(p) if self.ext == ".parquet" else \
                pd.read_csv(p, dtype={"case_id": str, "error": str, "status": str})
        except Exception as err:  # noqa: BLE001 - pyarrow's and pandas' own errors
            why = str(err).splitlines()[0] if str(err) else type(err).__name__
            raise InputError(f"the existing output cannot be read as a study's results "
                             f"({why}): remove it, or choose another output",
                             str(p)) from None
        if "case_id" not in df:
            raise InputError("the existing output has no case_id column: not a study's "
                             "results", str(p))
        return df

    def existing(self):
        """Rows already on disk (output file and chunks), one per case id."""
        import pandas as pd

        if self.path is None:
            return pd.DataFrame()
        frames = []
        if self.path.exists():
            frames.append(self._read(self.path))
        if self.parts.is_dir():
            frames += [self._read(p) for p in sorted(self.parts.glob(f"*{self.ext}"))]
        frames = [f for f in frames if len(f)]
        if not frames:
            return pd.DataFrame()
        df = pd.concat(frames, ignore_index=True)
        return df.drop_duplicates("case_id", keep="first")

    def write(self, rows: list[dict], columns: list[str]) -> None:
        if not rows:
            return
        if self.path is None:
            self.memory += rows
            return
        self.parts.mkdir(parents=True, exist_ok=True)
        name = f"part-{time.time_ns():020d}-{uuid.uuid4().hex[:8]}{self.ext}"
        tmp = self.parts / (name + ".tmp")
        _to_file(_frame(rows, columns), tmp, self.ext)
        os.replace(tmp, self.parts / name)

    def merge(self, columns: list[str], ids: Sequence[str]):
        """The sweep's rows in case order; written to OUTPUT (chunks removed)."""
        import pandas as pd

        if self.path is None:
            df = _frame(self.memory, columns)
        else:
            df = self.existing()
            if len(df):
                df = df[df["case_id"].isin(set(ids))]
            df = df.reindex(columns=columns) if len(df) else _frame([], columns)
        order = {cid: i for i, cid in enumerate(ids)}
        df = df.assign(case=[order[c] for c in df["case_id"]]) if len(df) else df
        df = df.sort_values("case", kind="stable").reset_index(drop=True)
        df = _tidy(df)
        if self.path is not None:
            tmp = self.path.with_name(self.path.name + ".tmp")
            _to_file(df, tmp, self.ext)
            os.replace(tmp, self.path)
            shutil.rmtree(self.parts, ignore_errors=True)
        return pd.DataFrame(df)


def _frame(rows: list[dict], columns: list[str]):
    import pandas as pd

    return _tidy(pd.DataFrame(rows, columns=columns))


def _tidy(df):
    """Columns of one type: numbers mixed with strings ("infinite") become strings."""
    for c in df.columns:
        if df[c].dtype == object:
            kinds = {type(v) for v in df[c] if v is not None and v == v}
            if str in kinds and len(kinds) > 1:
                df[c] = [None if (v is None or v != v) else str(v) for v in df[c]]
    return df


def _to_file(df, path: Path, ext: str) -> None:
    if ext == ".parquet":
        df.to_parquet(path, index=False)
    else:
        df.to_csv(path, index=False)
