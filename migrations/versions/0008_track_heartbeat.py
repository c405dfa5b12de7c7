"""track_samples: the autopilot's mode and vehicle type (its HEARTBEAT) and its GPS fix per sample

Revision ID: 0008
Revises: 0007
Create Date: 2026-11-29

"""
from typing import Sequence, Union

from alembic import op
import sqlalchemy as sa


# revision identifiers, used by Alembic.
revision: str = '0008'
down_revision: Union[str, Sequence[str], None] = '0007'
branch_labels: Union[str, Sequence[str], None] = None
depends_on: Union[str, Sequence[str], None] = None

COLUMNS = ('mav_type', 'custom_mode', 'gps_fix_type', 'satellites')


def upgrade() -> None:
    """Upgrade schema."""
    with op.batch_alter_table('track_samples') as batch:
        for name in COLUMNS:
            batch.add_column(sa.Column(name, sa.BigInteger(), nullable=True))


def downgrade() -> None:
    """Downgrade schema."""
    with op.batch_alter_table('track_samples') as batch:
        for name in COLUMNS:
            batch.drop_column(name)
