"""Which packages the distribution holds; everything else is in pyproject.toml.

The Alembic scripts live in ``migrations/`` at the top of the repository, beside ``gateway/``, and are
installed as the package ``gateway.migrations`` (a package-dir mapping, which pyproject.toml's package
discovery cannot express), so a wheel, an sdist and the image carry them inside ``gateway`` and the store
finds them wherever pip puts it (``gateway.registry.database.migrations_dir``).
"""

from setuptools import find_namespace_packages, setup

setup(
    packages=[
        *find_namespace_packages(include=["gateway", "gateway.*", "fleet_agent", "fleet_agent.*"]),
        "gateway.migrations",
        "gateway.migrations.versions",
    ],
    package_dir={"gateway.migrations": "migrations"},
)
