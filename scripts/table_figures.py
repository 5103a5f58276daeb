"""What the table scripts (views_table.py, stereo_table.py) share: a figure over runs as its mean
and spread (half the range), its text, and a run's load before and after from its summary.json."""


def mean_spread(values):
    if not values:
        return None, None
    return sum(values) / len(values), (max(values) - min(values)) / 2


def fmt(value, spread=None, digits=1):
    if value is None:
        return "-"
    text = f"{value:,.{digits}f}"
    return text + (f" ±{spread:,.{digits}f}" if spread is not None else "")


def load_text(summary):
    """The one-minute load average before and after the run, BUSY when the machine was."""
    m = summary["machine"]
    busy = " BUSY" if m.get("busy") else ""
    return f"{m['load_average_before'][0]:.2f}→{m['load_average_after'][0]:.2f}{busy}"
