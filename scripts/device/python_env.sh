# Sourced by the device scripts from a checkout's root: sets $python to the interpreter that
# runs the simulation stack. $PYTHON if set (a caller's choice, e.g. a script running another
# copy of the checkout), else the packed stack (scripts/device/pack_python.sh .pyb/py.tar.xz,
# unpacked into /tmp/b), else this checkout's .venv. Puts this checkout first on
# PYTHONPATH either way, so a copy of the checkout runs its own code.
if [ -n "${PYTHON:-}" ]; then
  python=$PYTHON
elif [ -f .pyb/py.tar.xz ]; then
  mkdir -p /tmp/b && tar xJf .pyb/py.tar.xz -C /tmp/b
  b=/tmp/b/py
  export LD_LIBRARY_PATH=$b/lib PYTHONHOME=$b PYTHONPATH=$b/site PYTHONNOUSERSITE=1
  python=$b/bin/python3.11
else
  python=$PWD/.venv/bin/python
fi
export PYTHONPATH=$PWD${PYTHONPATH:+:$PYTHONPATH}
