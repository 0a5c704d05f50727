"""The verdict of interoperability-schema.schema.json as code: written by
scripts/fast_validators.py, do not edit (see structure.fast_validator).
"""

# ruff: noqa
# fmt: off
# mypy: ignore-errors
SOURCE = 'd307ab20f27de0d41b4a277e9c66f6598ec1fb415d507f609f384baeeead5619'
import re

_NUMBER = (int, float)
_MISSING = object()
_C0 = frozenset({'edges', 'environment', 'format', 'name', 'nominal', 'roles', 'simulation', 'skill', 'title', 'version'})
_C1 = re.compile('^[A-Za-z][A-Za-z0-9_]*$').search
_C2 = set()  # texts _C1 matched
_C3 = frozenset({'abstraction', 'description', 'name'})
_C4 = frozenset({'consumer', 'interfaces', 'optional', 'providers'})
_C5 = re.compile('^/?[A-Za-z][A-Za-z0-9_]*(/[A-Za-z][A-Za-z0-9_]*)*$').search
_C6 = set()  # texts _C5 matched
_C7 = frozenset({'duration', 'loops', 'reference', 'requirements'})
_C8 = frozenset({'feedback', 'forward', 'name', 'plant'})
_C9 = frozenset({'delay', 'state_space', 'transfer_function'})
_C10 = frozenset({'den', 'num'})
_C11 = frozenset({'A', 'B', 'C', 'D'})
_C12 = frozenset({'overshoot', 'settling_time', 'steady_state_error'})


def validate(data):
    if not type(data) is dict:
        return False
    if not data.keys() <= _C0:
        return False
    v1 = data.get('format', _MISSING)
    if v1 is _MISSING:
        return False
    if not (type(v1) is str and v1 == 'rosreconf/interoperability-schema'):
        return False
    v2 = data.get('version', _MISSING)
    if v2 is _MISSING:
        return False
    if not (type(v2) in _NUMBER and v2 == 1):
        return False
    v3 = data.get('name', _MISSING)
    if v3 is _MISSING:
        return False
    if not type(v3) is str:
        return False
    if v3 not in _C2:
        if _C1(v3) is None:
            return False
        if len(_C2) < 100000:
            _C2.add(v3)
    v4 = data.get('title', _MISSING)
    if v4 is not _MISSING:
        if not type(v4) is str:
            return False
    v5 = data.get('skill', _MISSING)
    if v5 is _MISSING:
        return False
    if not type(v5) is str:
        return False
    v6 = data.get('environment', _MISSING)
    if v6 is _MISSING:
        return False
    if not type(v6) is str:
        return False
    v7 = data.get('roles', _MISSING)
    if v7 is _MISSING:
        return False
    if not type(v7) is list:
        return False
    if len(v7) < 1:
        return False
    for v8 in v7:
        if not type(v8) is dict:
            return False
        if not v8.keys() <= _C3:
            return False
        v9 = v8.get('name', _MISSING)
        if v9 is _MISSING:
            return False
        if not type(v9) is str:
            return False
        if v9 not in _C2:
            if _C1(v9) is None:
                return False
            if len(_C2) < 100000:
                _C2.add(v9)
        v10 = v8.get('abstraction', _MISSING)
        if v10 is _MISSING:
            return False
        if not type(v10) is str:
            return False
        if v10 not in _C2:
            if _C1(v10) is None:
                return False
            if len(_C2) < 100000:
                _C2.add(v10)
        v11 = v8.get('description', _MISSING)
        if v11 is not _MISSING:
            if not type(v11) is str:
                return False
    v12 = data.get('edges', _MISSING)
    if v12 is not _MISSING:
        if not type(v12) is list:
            return False
        for v13 in v12:
            if not type(v13) is dict:
                return False
            if not v13.keys() <= _C4:
                return False
            v14 = v13.get('consumer', _MISSING)
            if v14 is _MISSING:
                return False
            if not type(v14) is str:
                return False
            if v14 not in _C2:
                if _C1(v14) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v14)
            v15 = v13.get('providers', _MISSING)
            if v15 is _MISSING:
                return False
            if not type(v15) is list:
                return False
            if len(v15) < 1:
                return False
            for v16 in v15:
                if not type(v16) is str:
                    return False
                if v16 not in _C2:
                    if _C1(v16) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v16)
            if len(set(v15)) != len(v15):
                return False
            v17 = v13.get('interfaces', _MISSING)
            if v17 is not _MISSING:
                if not type(v17) is list:
                    return False
                if len(v17) < 1:
                    return False
                for v18 in v17:
                    if not type(v18) is str:
                        return False
                    if v18 not in _C6:
                        if _C5(v18) is None:
                            return False
                        if len(_C6) < 100000:
                            _C6.add(v18)
                if len(set(v17)) != len(v17):
                    return False
            v19 = v13.get('optional', _MISSING)
            if v19 is not _MISSING:
                if not type(v19) is bool:
                    return False
    v20 = data.get('nominal', _MISSING)
    if v20 is not _MISSING:
        if not type(v20) is dict:
            return False
        for v22 in v20.values():
            if not type(v22) is str:
                return False
            if v22 not in _C2:
                if _C1(v22) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v22)
        for v23 in v20:
            if not type(v23) is str:
                return False
            if v23 not in _C2:
                if _C1(v23) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v23)
    v24 = data.get('simulation', _MISSING)
    if v24 is not _MISSING:
        if not type(v24) is dict:
            return False
        if not v24.keys() <= _C7:
            return False
        v25 = v24.get('loops', _MISSING)
        if v25 is _MISSING:
            return False
        if not type(v25) is list:
            return False
        if len(v25) < 1:
            return False
        for v26 in v25:
            if not type(v26) is dict:
                return False
            if not v26.keys() <= _C8:
                return False
            v27 = v26.get('name', _MISSING)
            if v27 is _MISSING:
                return False
            if not type(v27) is str:
                return False
            if v27 not in _C2:
                if _C1(v27) is None:
                    return False
                if len(_C2) < 100000:
                    _C2.add(v27)
            v28 = v26.get('forward', _MISSING)
            if v28 is _MISSING:
                return False
            if not type(v28) is list:
                return False
            if len(v28) < 1:
                return False
            for v29 in v28:
                if not type(v29) is str:
                    return False
                if v29 not in _C2:
                    if _C1(v29) is None:
                        return False
                    if len(_C2) < 100000:
                        _C2.add(v29)
            if len(set(v28)) != len(v28):
                return False
            v30 = v26.get('plant', _MISSING)
            if v30 is _MISSING:
                return False
            if not type(v30) is dict:
                return False
            if ((not ('transfer_function' not in v30)) + (not ('state_space' not in v30))) != 1:
                return False
            if not v30.keys() <= _C9:
                return False
            v31 = v30.get('transfer_function', _MISSING)
            if v31 is not _MISSING:
                if not type(v31) is dict:
                    return False
                if not v31.keys() <= _C10:
                    return False
                v32 = v31.get('num', _MISSING)
                if v32 is _MISSING:
                    return False
                if not type(v32) is list:
                    return False
                if len(v32) < 1:
                    return False
                for v33 in v32:
                    if not type(v33) in _NUMBER:
                        return False
                v34 = v31.get('den', _MISSING)
                if v34 is _MISSING:
                    return False
                if not type(v34) is list:
                    return False
                if len(v34) < 1:
                    return False
                for v35 in v34:
                    if not type(v35) in _NUMBER:
                        return False
            v36 = v30.get('state_space', _MISSING)
            if v36 is not _MISSING:
                if not type(v36) is dict:
                    return False
                if not v36.keys() <= _C11:
                    return False
                v37 = v36.get('A', _MISSING)
                if v37 is _MISSING:
                    return False
                if not type(v37) is list:
                    return False
                if len(v37) < 1:
                    return False
                for v38 in v37:
                    if not type(v38) is list:
                        return False
                    if len(v38) < 1:
                        return False
                    for v39 in v38:
                        if not type(v39) in _NUMBER:
                            return False
                v40 = v36.get('B', _MISSING)
                if v40 is _MISSING:
                    return False
                if not type(v40) is list:
                    return False
                if len(v40) < 1:
                    return False
                for v41 in v40:
                    if not type(v41) is list:
                        return False
                    if len(v41) < 1:
                        return False
                    for v42 in v41:
                        if not type(v42) in _NUMBER:
                            return False
                v43 = v36.get('C', _MISSING)
                if v43 is _MISSING:
                    return False
                if not type(v43) is list:
                    return False
                if len(v43) < 1:
                    return False
                for v44 in v43:
                    if not type(v44) is list:
                        return False
                    if len(v44) < 1:
                        return False
                    for v45 in v44:
                        if not type(v45) in _NUMBER:
                            return False
                v46 = v36.get('D', _MISSING)
                if v46 is _MISSING:
                    return False
                if not type(v46) is list:
                    return False
                if len(v46) < 1:
                    return False
                for v47 in v46:
                    if not type(v47) is list:
                        return False
                    if len(v47) < 1:
                        return False
                    for v48 in v47:
                        if not type(v48) in _NUMBER:
                            return False
            v49 = v30.get('delay', _MISSING)
            if v49 is not _MISSING:
                if not type(v49) in _NUMBER:
                    return False
                if v49 < 0:
                    return False
            v50 = v26.get('feedback', _MISSING)
            if v50 is not _MISSING:
                if not type(v50) is list:
                    return False
                for v51 in v50:
                    if not type(v51) is str:
                        return False
                    if v51 not in _C2:
                        if _C1(v51) is None:
                            return False
                        if len(_C2) < 100000:
                            _C2.add(v51)
                if len(set(v50)) != len(v50):
                    return False
        v52 = v24.get('reference', _MISSING)
        if v52 is not _MISSING:
            if not type(v52) in _NUMBER:
                return False
            if v52 <= 0:
                return False
        v53 = v24.get('duration', _MISSING)
        if v53 is _MISSING:
            return False
        if not type(v53) in _NUMBER:
            return False
        if v53 <= 0:
            return False
        v54 = v24.get('requirements', _MISSING)
        if v54 is not _MISSING:
            if not type(v54) is dict:
                return False
            if not v54.keys() <= _C12:
                return False
            v55 = v54.get('settling_time', _MISSING)
            if v55 is not _MISSING:
                if not type(v55) in _NUMBER:
                    return False
                if v55 < 0:
                    return False
            v56 = v54.get('steady_state_error', _MISSING)
            if v56 is not _MISSING:
                if not type(v56) in _NUMBER:
                    return False
                if v56 < 0:
                    return False
            v57 = v54.get('overshoot', _MISSING)
            if v57 is not _MISSING:
                if not type(v57) in _NUMBER:
                    return False
                if v57 < 0:
                    return False
    return True


VALIDATE = validate
