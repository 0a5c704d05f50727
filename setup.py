"""Build rosreconf's optional compiled YAML reader; everything else is in pyproject.toml.

setuptools takes C extensions only from setup.py. The extension is optional, as PyYAML's
libyaml binding is: without a C compiler or libyaml's headers (Debian: libyaml-dev) the
build warns and rosreconf installs with its Python readers, which give the same answers
about three times slower on large libraries (docs/formats.md).
"""

from setuptools import Extension, setup

setup(
    ext_modules=[
        Extension(
            "rosreconf.formats._yamlc",
            ["rosreconf/formats/_yamlc.c"],
            libraries=["yaml"],
            optional=True,
        )
    ]
)
